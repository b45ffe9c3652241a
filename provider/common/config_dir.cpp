#include "provider/common/config_dir.hpp"

#include <sys/stat.h>

#include <cerrno>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <iterator>
#include <system_error>

#include "native/private_file.hpp"
#include "shared/io/atomic_file.hpp"

namespace umf::provider {

namespace fs = std::filesystem;

fs::path default_config_dir() {
    if (const char* xdg = std::getenv("XDG_CONFIG_HOME"); xdg && *xdg && fs::path(xdg).is_absolute())
        return fs::path(xdg) / "umf";
    if (const char* home = std::getenv("HOME"); home && *home) return fs::path(home) / ".config" / "umf";
    throw ConfigError("neither XDG_CONFIG_HOME nor HOME is set; give --config-dir");
}

void ensure_config_dir(const fs::path& dir) {
    std::error_code ec;
    if (fs::is_directory(dir, ec)) return;
    if (dir.has_parent_path() && dir.parent_path() != dir) fs::create_directories(dir.parent_path(), ec);
    if (::mkdir(dir.c_str(), 0700) != 0 && errno != EEXIST)
        throw ConfigError(dir.string() + ": cannot create the directory: " + std::strerror(errno));
    if (!fs::is_directory(dir, ec)) throw ConfigError(dir.string() + ": not a directory");
}

void write_private_file(const fs::path& path, const std::string& bytes) {
    try {
        umf::write_private_file(path, bytes);
    } catch (const FileWriteError& e) {
        throw ConfigError(e.what());
    }
}

std::optional<std::string> read_small_file(const fs::path& path, std::size_t max_bytes) {
    std::error_code ec;
    if (!fs::exists(path, ec)) return std::nullopt;
    const auto size = fs::file_size(path, ec);
    if (ec) throw ConfigError(path.string() + ": cannot read: " + ec.message());
    if (size > max_bytes) throw ConfigError(path.string() + ": larger than " + std::to_string(max_bytes) + " bytes");
    std::ifstream in(path, std::ios::binary);
    if (!in) throw ConfigError(path.string() + ": cannot open");
    std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    if (in.bad()) throw ConfigError(path.string() + ": read error");
    return text;
}

}  // namespace umf::provider
