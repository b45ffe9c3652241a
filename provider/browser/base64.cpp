#include "provider/browser/base64.hpp"

namespace umf::provider {

std::optional<std::string> base64_decode(std::string_view text) {
    std::string out;
    out.reserve(text.size() / 4 * 3);
    unsigned value = 0;
    int bits = 0;
    std::size_t padding = 0;
    for (const char c : text) {
        unsigned d;
        if (c >= 'A' && c <= 'Z') d = static_cast<unsigned>(c - 'A');
        else if (c >= 'a' && c <= 'z') d = static_cast<unsigned>(c - 'a' + 26);
        else if (c >= '0' && c <= '9') d = static_cast<unsigned>(c - '0' + 52);
        else if (c == '+') d = 62;
        else if (c == '/') d = 63;
        else if (c == '=' && ++padding <= 2) continue;
        else return std::nullopt;
        if (padding) return std::nullopt;  // data after padding
        value = (value << 6 | d) & 0xffffff;
        bits += 6;
        if (bits >= 8) {
            bits -= 8;
            out += static_cast<char>((value >> bits) & 0xff);
        }
    }
    return out;
}

}  // namespace umf::provider
