#include "common/config_dir.hpp"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <iterator>
#include <system_error>

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
    const fs::path tmp = path.string() + ".tmp";
    ::unlink(tmp.c_str());
    const int fd = ::open(tmp.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_CLOEXEC, 0600);
    if (fd < 0) throw ConfigError(path.string() + ": cannot create " + tmp.string() + ": " + std::strerror(errno));
    std::size_t done = 0;
    bool ok = true;
    while (ok && done < bytes.size()) {
        const ssize_t n = ::write(fd, bytes.data() + done, bytes.size() - done);
        if (n < 0 && errno == EINTR) continue;
        ok = n > 0;
        if (ok) done += static_cast<std::size_t>(n);
    }
    ok = ok && ::fchmod(fd, 0600) == 0 && ::fsync(fd) == 0;
    const int saved = errno;
    ok = ::close(fd) == 0 && ok;
    if (!ok || std::rename(tmp.c_str(), path.c_str()) != 0) {
        const int err = ok ? errno : saved;
        ::unlink(tmp.c_str());
        throw ConfigError(path.string() + ": cannot write: " + std::strerror(err));
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
