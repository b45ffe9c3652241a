#include "provider/content/read_lease.hpp"

#include <fcntl.h>

#include <csignal>
#include <utility>

namespace umf::provider {

ReadLease::ReadLease(int fd) {
    // The signal first: a break between the two calls must not send SIGIO,
    // whose default is to end the process.
    if (fd < 0 || ::fcntl(fd, F_SETSIG, SIGURG) != 0) return;
    if (::fcntl(fd, F_SETLEASE, F_RDLCK) == 0) fd_ = fd;
}

ReadLease::ReadLease(ReadLease&& other) noexcept : fd_(std::exchange(other.fd_, -1)) {}

ReadLease& ReadLease::operator=(ReadLease&& other) noexcept {
    if (this != &other) {
        release();
        fd_ = std::exchange(other.fd_, -1);
    }
    return *this;
}

bool ReadLease::unbroken() const {
    // While a break is pending the kernel reports the type the lease is to
    // become: F_UNLCK for a read lease.
    return fd_ >= 0 && ::fcntl(fd_, F_GETLEASE) == F_RDLCK;
}

void ReadLease::release() {
    if (fd_ < 0) return;
    ::fcntl(fd_, F_SETLEASE, F_UNLCK);
    fd_ = -1;
}

}  // namespace umf::provider
