#include "requester/transfer_text.hpp"

#include <cstdio>

namespace umf::requester {

std::string megabytes(std::uint64_t bytes) {
    char text[32];
    std::snprintf(text, sizeof text, "%.1f MB", static_cast<double>(bytes) / 1e6);
    return text;
}

std::string transfer_rate(std::uint64_t bytes, std::chrono::steady_clock::duration took) {
    const double seconds = std::chrono::duration<double>(took).count();
    char text[64];
    std::snprintf(text, sizeof text, " in %.2f s, %.1f MB/s", seconds,
                  seconds > 0 ? static_cast<double>(bytes) / 1e6 / seconds : 0.0);
    return megabytes(bytes) + text;
}

std::string seconds_text(std::chrono::milliseconds ms) {
    return std::to_string(ms.count() / 1000) + (ms.count() % 1000 ? "." + std::to_string(ms.count() % 1000 / 100) : "") +
           " s";
}

}  // namespace umf::requester
