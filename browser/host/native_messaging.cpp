#include "browser/host/native_messaging.hpp"

#include <cstdint>
#include <cstring>

namespace umf::browser {

std::string frame_message(const std::string& json, std::size_t max) {
    if (json.size() > max)
        throw FramingError("a message of " + std::to_string(json.size()) + " bytes is longer than " + std::to_string(max));
    const auto length = static_cast<std::uint32_t>(json.size());
    std::string out(4, '\0');
    std::memcpy(out.data(), &length, 4);
    return out + json;
}

std::optional<std::string> FrameReader::next() {
    if (buffer_.size() < 4) return std::nullopt;
    std::uint32_t length = 0;
    std::memcpy(&length, buffer_.data(), 4);
    if (length > max_)
        throw FramingError("the browser announced a message of " + std::to_string(length) + " bytes, more than " +
                           std::to_string(max_));
    if (buffer_.size() < 4 + static_cast<std::size_t>(length)) return std::nullopt;
    std::string message = buffer_.substr(4, length);
    buffer_.erase(0, 4 + static_cast<std::size_t>(length));
    return message;
}

}  // namespace umf::browser
