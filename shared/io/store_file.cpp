#include "shared/io/store_file.hpp"

#include <fcntl.h>
#include <stdio.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>

#include "shared/io/unique_name.hpp"

namespace umf::io {

namespace {

// Whether the move failed because the name is taken; throws on any other
// failure than a file system without an exclusive rename.
bool taken(int error, const std::filesystem::path& target, bool rename_unsupported_ok) {
    if (error == EEXIST) return true;
    if (rename_unsupported_ok && (error == EINVAL || error == ENOSYS || error == ENOTSUP)) return false;
    throw std::runtime_error("cannot store " + target.string() + ": " + std::strerror(error));
}

}  // namespace

std::string store_under_free_name(const std::filesystem::path& temp, const std::filesystem::path& dir,
                                  const std::string& name) {
    for (int n = 0; n < 10000; ++n) {
        const std::string candidate = numbered_name(name, n);
        const std::filesystem::path target = dir / candidate;
#if defined(RENAME_NOREPLACE) && !defined(__EMSCRIPTEN__)
        if (::renameat2(AT_FDCWD, temp.c_str(), AT_FDCWD, target.c_str(), RENAME_NOREPLACE) == 0) return candidate;
        if (taken(errno, target, true)) continue;
#endif
        // No exclusive rename here: a hard link fails on an existing name just the same.
        if (::link(temp.c_str(), target.c_str()) == 0) {
            ::unlink(temp.c_str());
            return candidate;
        }
        if (taken(errno, target, false)) continue;
    }
    throw std::runtime_error("cannot store " + name + " in " + dir.string() + ": 10000 files of that name exist");
}

}  // namespace umf::io
