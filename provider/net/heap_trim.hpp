// Memory freed by ended connections, given back to the system. A flood of
// connections leaves the allocator holding the pages their buffers used,
// and a kiosk runs for months: without this its resident size stays at the
// flood's high-water mark (docs/BENCHMARKS.md, "Provider through connection
// floods"). Every `every`, if enough connections ended since the last look,
// the heap is trimmed; a quiet provider is never touched.
#pragma once

#include <boost/asio/io_context.hpp>
#include <boost/asio/steady_timer.hpp>
#include <atomic>
#include <chrono>
#include <cstdint>
#include <memory>

namespace umf::provider {

class ConnectionRegistry;

// Gives free heap pages back (glibc's malloc_trim); false where there is no
// such call. Returns whether anything was released.
bool trim_heap();

class HeapTrimmer : public std::enable_shared_from_this<HeapTrimmer> {
public:
    HeapTrimmer(boost::asio::io_context& io, std::shared_ptr<const ConnectionRegistry> registry,
                std::chrono::milliseconds every = std::chrono::seconds(5), std::uint64_t after_ended = 32);
    void start();
    // From any thread; the timer's pending wait ends at once.
    void stop();
    // Trims done so far (for tests and the log).
    std::uint64_t trims() const { return trims_.load(); }

private:
    void arm();
    boost::asio::steady_timer timer_;
    std::shared_ptr<const ConnectionRegistry> registry_;
    std::chrono::milliseconds every_;
    std::uint64_t after_ended_;
    std::uint64_t seen_ended_ = 0;
    std::atomic<std::uint64_t> trims_{0};
};

}  // namespace umf::provider
