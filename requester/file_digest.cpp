#include "requester/file_digest.hpp"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <stdexcept>
#include <vector>

#include "native/sha256.hpp"

namespace umf::requester {

FileDigest digest_file(const std::filesystem::path& file) {
    const int fd = ::open(file.c_str(), O_RDONLY | O_CLOEXEC);
    if (fd < 0) throw std::runtime_error("cannot open " + file.string() + ": " + std::strerror(errno));
    struct Closer {
        int fd;
        ~Closer() { ::close(fd); }
    } closer{fd};
    struct stat st {};
    if (::fstat(fd, &st) != 0) throw std::runtime_error("cannot read " + file.string() + ": " + std::strerror(errno));
    if (!S_ISREG(st.st_mode)) throw std::runtime_error(file.string() + " is not a regular file");
    native::Sha256 hash;
    FileDigest d;
    d.checkpoints = std::make_shared<native::HashCheckpoints>();
    // Reads end on multiples of the buffer's size, so each step's state is kept.
    std::vector<char> buffer(1 << 20);
    static_assert(native::HashCheckpoints::kStep % (1 << 20) == 0);
    for (;;) {
        const ssize_t n = ::read(fd, buffer.data(), buffer.size() - static_cast<std::size_t>(d.size) % buffer.size());
        if (n < 0 && errno == EINTR) continue;
        if (n < 0) throw std::runtime_error("cannot read " + file.string() + ": " + std::strerror(errno));
        if (n == 0) break;
        hash.update(buffer.data(), static_cast<std::size_t>(n));
        d.size += n;
        d.checkpoints->save(static_cast<std::uint64_t>(d.size), hash);
    }
    d.sha256 = hash.hex();
    return d;
}

}  // namespace umf::requester
