#include "provider/desktop/wlroots/shm_buffer.hpp"

#include <sys/mman.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <string>

#include "provider/desktop/desktop.hpp"

namespace umf::provider {

std::unique_ptr<ShmBuffer> ShmBuffer::create(wl_shm* shm, int width, int height, int stride, std::uint32_t format) {
    if (!shm || width <= 0 || height <= 0 || stride < width * 4)
        throw DesktopError("cannot make a " + std::to_string(width) + "x" + std::to_string(height) + " shared-memory buffer");
    std::unique_ptr<ShmBuffer> b(new ShmBuffer);
    b->width_ = width, b->height_ = height, b->stride_ = stride;
    b->size_ = static_cast<std::size_t>(stride) * height;
    const int fd = ::memfd_create("umf-wayland-buffer", MFD_CLOEXEC);
    if (fd < 0) throw DesktopError(std::string("memfd_create failed: ") + std::strerror(errno));
    if (::ftruncate(fd, static_cast<off_t>(b->size_)) != 0) {
        ::close(fd);
        throw DesktopError(std::string("cannot size a shared-memory buffer: ") + std::strerror(errno));
    }
    b->data_ = ::mmap(nullptr, b->size_, PROT_READ | PROT_WRITE, MAP_SHARED, fd, 0);
    if (b->data_ == MAP_FAILED) {
        b->data_ = nullptr;
        ::close(fd);
        throw DesktopError(std::string("cannot map a shared-memory buffer: ") + std::strerror(errno));
    }
    wl_shm_pool* pool = wl_shm_create_pool(shm, fd, static_cast<std::int32_t>(b->size_));
    b->buffer_ = wl_shm_pool_create_buffer(pool, 0, width, height, stride, format);
    wl_shm_pool_destroy(pool);
    ::close(fd);
    static const wl_buffer_listener listener = {
        [](void* data, wl_buffer*) { static_cast<ShmBuffer*>(data)->busy_ = false; }};
    wl_buffer_add_listener(b->buffer_, &listener, b.get());
    return b;
}

ShmBuffer::~ShmBuffer() {
    if (buffer_) wl_buffer_destroy(buffer_);
    if (data_) ::munmap(data_, size_);
}

}  // namespace umf::provider
