// The browsers' native messaging framing: each message is UTF-8 JSON
// preceded by its length, 4 bytes in the machine's byte order. Pure.
#pragma once

#include <cstddef>
#include <optional>
#include <stdexcept>
#include <string>

namespace umf::browser {

// Most a browser takes in one message from a host (Chromium: 1 MB).
inline constexpr std::size_t kMaxToBrowser = 1024 * 1024;
// Most this host takes from its extension in one message.
inline constexpr std::size_t kMaxFromBrowser = 48 * 1024 * 1024;  // an image of 32 MiB in base64

class FramingError : public std::runtime_error {
public:
    using std::runtime_error::runtime_error;
};

// The framed bytes of one message. Throws FramingError when longer than `max`.
std::string frame_message(const std::string& json, std::size_t max = kMaxToBrowser);

// Collects bytes as they come and hands out whole messages.
class FrameReader {
public:
    explicit FrameReader(std::size_t max = kMaxFromBrowser) : max_(max) {}
    void feed(const char* data, std::size_t size) { buffer_.append(data, size); }
    // The next whole message, or nullopt until more bytes come. Throws
    // FramingError when a message announces more than the maximum.
    std::optional<std::string> next();
    // Bytes of an unfinished message (a browser that quit mid-message).
    std::size_t pending() const { return buffer_.size(); }

private:
    std::size_t max_;
    std::string buffer_;
};

}  // namespace umf::browser
