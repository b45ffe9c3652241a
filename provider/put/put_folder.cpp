#include "provider/put/put_folder.hpp"

#include <pwd.h>
#include <unistd.h>

#include <cstdlib>
#include <fstream>
#include <sstream>

namespace umf::provider {

namespace {

std::filesystem::path without_trailing_slash(const std::filesystem::path& p) {
    std::filesystem::path n = p.lexically_normal();
    if (!n.has_filename() && n != n.root_path()) n = n.parent_path();
    return n;
}

}  // namespace

std::optional<std::filesystem::path> download_dir_from_user_dirs(const std::string& text,
                                                                 const std::filesystem::path& home) {
    std::optional<std::filesystem::path> found;
    std::istringstream lines(text);
    std::string line;
    while (std::getline(lines, line)) {
        const auto first = line.find_first_not_of(" \t");
        if (first == std::string::npos || line[first] == '#') continue;
        line.erase(0, first);
        const std::string key = "XDG_DOWNLOAD_DIR=";
        if (line.rfind(key, 0) != 0) continue;
        std::string value = line.substr(key.size());
        while (!value.empty() && (value.back() == ' ' || value.back() == '\t' || value.back() == '\r')) value.pop_back();
        // The format: "$HOME/path" or "/path", in double quotes; backslash
        // escapes only ", \, $ and `.
        if (value.size() < 2 || value.front() != '"' || value.back() != '"') continue;
        value = value.substr(1, value.size() - 2);
        std::string unescaped;
        for (std::size_t i = 0; i < value.size(); ++i) {
            if (value[i] == '\\' && i + 1 < value.size()) ++i;
            unescaped += value[i];
        }
        std::filesystem::path path;
        if (unescaped == "$HOME")
            path = home;
        else if (unescaped.rfind("$HOME/", 0) == 0)
            path = home / unescaped.substr(6);
        else if (!unescaped.empty() && unescaped.front() == '/')
            path = unescaped;
        else
            continue;
        path = without_trailing_slash(path);
        // The last assignment counts, as when the shell reads the file.
        found = path == without_trailing_slash(home) ? std::nullopt : std::optional(path);
    }
    return found;
}

std::filesystem::path default_put_folder() {
    std::filesystem::path home;
    if (const char* h = std::getenv("HOME"); h && *h) {
        home = h;
    } else if (const passwd* pw = ::getpwuid(::getuid()); pw && pw->pw_dir) {
        home = pw->pw_dir;
    } else {
        home = "/tmp";
    }
    const char* config = std::getenv("XDG_CONFIG_HOME");
    const std::filesystem::path config_dir = config && *config && config[0] == '/' ? std::filesystem::path(config)
                                                                                   : home / ".config";
    std::ifstream file(config_dir / "user-dirs.dirs");
    if (file) {
        std::stringstream text;
        text << file.rdbuf();
        if (auto dir = download_dir_from_user_dirs(text.str(), home)) return *dir;
    }
    return home / "Downloads";
}

}  // namespace umf::provider
