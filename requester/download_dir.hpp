// Where downloads go unless --out says otherwise: the desktop's download
// directory as xdg-user-dirs records it, else ~/Downloads. The parsing is
// header-only and pure so the tests check it without touching $HOME.
#pragma once

#include <pwd.h>
#include <unistd.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <optional>
#include <sstream>
#include <string>
#include <string_view>

namespace umf::requester {

// XDG_DOWNLOAD_DIR from the text of a user-dirs.dirs file: lines of
// XDG_NAME_DIR="$HOME/dir" or XDG_NAME_DIR="/abs/dir" (the only two forms the
// format allows), '#' comments. "$HOME/" alone means the directory is
// switched off: nothing then, so the caller falls back.
inline std::optional<std::string> parse_user_dirs_download(std::string_view text, std::string_view home) {
    std::optional<std::string> found;
    std::size_t pos = 0;
    while (pos <= text.size()) {
        const auto nl = text.find('\n', pos);
        std::string_view line = text.substr(pos, nl == std::string_view::npos ? std::string_view::npos : nl - pos);
        pos = nl == std::string_view::npos ? text.size() + 1 : nl + 1;
        while (!line.empty() && (line.front() == ' ' || line.front() == '\t')) line.remove_prefix(1);
        while (!line.empty() && (line.back() == ' ' || line.back() == '\t' || line.back() == '\r')) line.remove_suffix(1);
        constexpr std::string_view key = "XDG_DOWNLOAD_DIR=";
        if (line.substr(0, key.size()) != key) continue;
        line.remove_prefix(key.size());
        if (line.size() < 2 || line.front() != '"' || line.back() != '"') continue;
        line = line.substr(1, line.size() - 2);
        std::string value;
        for (std::size_t i = 0; i < line.size(); ++i) {
            if (line[i] == '\\' && i + 1 < line.size()) ++i;  // \" \\ \$ \`
            value += line[i];
        }
        std::string path;
        if (value.rfind("$HOME", 0) == 0 && (value.size() == 5 || value[5] == '/')) {
            const std::string rest = value.substr(5);
            if (rest.find_first_not_of('/') == std::string::npos) {
                found.reset();  // switched off
                continue;
            }
            path = std::string(home) + rest;
        } else if (!value.empty() && value.front() == '/') {
            path = value;
        } else {
            continue;
        }
        found = path;  // the last assignment wins, as when the shell sources it
    }
    return found;
}

// $HOME, or the password database's home when it is unset.
inline std::string home_directory() {
    if (const char* h = std::getenv("HOME"); h && *h) return h;
    if (const passwd* pw = getpwuid(getuid()); pw && pw->pw_dir) return pw->pw_dir;
    return "/";
}

// $XDG_CONFIG_HOME when it is an absolute path, else ~/.config.
inline std::filesystem::path config_home() {
    if (const char* x = std::getenv("XDG_CONFIG_HOME"); x && *x == '/') return x;
    return std::filesystem::path(home_directory()) / ".config";
}

// The default --out: $XDG_CONFIG_HOME/user-dirs.dirs (~/.config/...) says
// where, else ~/Downloads. Not created here.
inline std::filesystem::path default_download_dir() {
    const std::string home = home_directory();
    std::ifstream in(config_home() / "user-dirs.dirs");
    if (in) {
        std::ostringstream text;
        text << in.rdbuf();
        if (auto dir = parse_user_dirs_download(text.str(), home)) return *dir;
    }
    return std::filesystem::path(home) / "Downloads";
}

}  // namespace umf::requester
