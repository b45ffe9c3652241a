// A wl_buffer in shared memory (memfd), mapped here: what the field draws
// into and what screencopy copies into. busy() while the compositor holds it
// (from attach to its release event).
#pragma once

#include <wayland-client.h>

#include <cstddef>
#include <cstdint>
#include <memory>

namespace umf::provider {

class ShmBuffer {
public:
    // Throws DesktopError when the memory cannot be had.
    static std::unique_ptr<ShmBuffer> create(wl_shm* shm, int width, int height, int stride, std::uint32_t format);
    ~ShmBuffer();
    ShmBuffer(const ShmBuffer&) = delete;
    ShmBuffer& operator=(const ShmBuffer&) = delete;

    wl_buffer* buffer() const { return buffer_; }
    std::uint8_t* data() const { return static_cast<std::uint8_t*>(data_); }
    std::uint32_t* row(int y) const { return reinterpret_cast<std::uint32_t*>(data() + static_cast<std::size_t>(y) * stride_); }
    int width() const { return width_; }
    int height() const { return height_; }
    int stride() const { return stride_; }
    bool busy() const { return busy_; }
    // Attaching it: busy until the compositor releases it.
    void mark_busy() { busy_ = true; }

private:
    ShmBuffer() = default;

    wl_buffer* buffer_ = nullptr;
    void* data_ = nullptr;
    std::size_t size_ = 0;
    int width_ = 0, height_ = 0, stride_ = 0;
    bool busy_ = false;
};

}  // namespace umf::provider
