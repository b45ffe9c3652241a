#include "provider/net/heap_trim.hpp"

#include <boost/asio/post.hpp>

#include "provider/net/connection_registry.hpp"

#if defined(__GLIBC__)
#include <malloc.h>
#endif

namespace umf::provider {

bool trim_heap() {
#if defined(__GLIBC__)
    return malloc_trim(0) != 0;
#else
    return false;
#endif
}

HeapTrimmer::HeapTrimmer(boost::asio::io_context& io, std::shared_ptr<const ConnectionRegistry> registry,
                         std::chrono::milliseconds every, std::uint64_t after_ended)
    : timer_(io), registry_(std::move(registry)), every_(every), after_ended_(after_ended) {}

void HeapTrimmer::start() {
    seen_ended_ = registry_->ended();
    arm();
}

void HeapTrimmer::stop() {
    boost::asio::post(timer_.get_executor(), [self = shared_from_this()] { self->timer_.cancel(); });
}

void HeapTrimmer::arm() {
    timer_.expires_after(every_);
    timer_.async_wait([self = shared_from_this()](boost::system::error_code ec) {
        if (ec) return;
        const std::uint64_t ended = self->registry_->ended();
        if (ended - self->seen_ended_ >= self->after_ended_) {
            // Trimmed once the connections are gone, not while they still
            // end: a flood still under way is seen again next time.
            self->seen_ended_ = ended;
            trim_heap();
            ++self->trims_;
        }
        self->arm();
    });
}

}  // namespace umf::provider
