#include "provider/desktop/gnome/private_folder.hpp"

#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cstdlib>
#include <cstring>

#include "provider/desktop/desktop.hpp"

namespace umf::provider {

std::filesystem::path private_runtime_folder() {
    const char* runtime = std::getenv("XDG_RUNTIME_DIR");
    if (!runtime || !*runtime)
        throw DesktopError("XDG_RUNTIME_DIR is not set: the GNOME Shell extension and the provider share files there");
    const std::filesystem::path folder = std::filesystem::path(runtime) / "umf";
    if (::mkdir(folder.c_str(), 0700) != 0 && errno != EEXIST)
        throw DesktopError("cannot make " + folder.string() + ": " + std::strerror(errno));
    struct stat info {};
    if (::lstat(folder.c_str(), &info) != 0)
        throw DesktopError("cannot read " + folder.string() + ": " + std::strerror(errno));
    if (!S_ISDIR(info.st_mode)) throw DesktopError(folder.string() + " is not a folder (a symbolic link?); remove it");
    if (info.st_uid != ::geteuid()) throw DesktopError(folder.string() + " belongs to another user; remove it");
    if ((info.st_mode & (S_IWGRP | S_IWOTH)) != 0 && ::chmod(folder.c_str(), 0700) != 0)
        throw DesktopError(folder.string() + " is writable by others and cannot be made private");
    return folder;
}

}  // namespace umf::provider
