#include "provider/net/lingering_close.hpp"

#include <array>
#include <chrono>

namespace umf::provider {

namespace beast = boost::beast;
namespace net = boost::asio;

namespace {

constexpr auto kLingerTime = std::chrono::seconds(5);
constexpr std::size_t kMaxLingerBytes = 64 << 20;

class Linger : public std::enable_shared_from_this<Linger> {
public:
    Linger(beast::tcp_stream& stream, std::shared_ptr<void> owner) : stream_(stream), owner_(std::move(owner)) {}

    void drain() {
        stream_.async_read_some(net::buffer(buffer_), [self = shared_from_this()](beast::error_code ec, std::size_t n) {
            self->bytes_ += n;
            if (ec || self->bytes_ > kMaxLingerBytes) {
                self->stream_.close();
                return;
            }
            self->drain();
        });
    }

private:
    beast::tcp_stream& stream_;
    std::shared_ptr<void> owner_;
    std::array<char, 16 * 1024> buffer_;
    std::size_t bytes_ = 0;
};

}  // namespace

void lingering_close(beast::tcp_stream& stream, std::shared_ptr<void> owner) {
    beast::error_code ignored;
    stream.socket().shutdown(net::ip::tcp::socket::shutdown_send, ignored);
    stream.expires_after(kLingerTime);
    std::make_shared<Linger>(stream, std::move(owner))->drain();
}

}  // namespace umf::provider
