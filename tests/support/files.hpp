// Whole files in and out, and reproducible bytes to fill them, for tests
// that check a file arrived unchanged.
#pragma once

#include <cstdint>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

namespace umf::test {

inline std::string read_file(const std::filesystem::path& p) {
    std::ifstream in(p, std::ios::binary);
    std::ostringstream s;
    s << in.rdbuf();
    return s.str();
}

inline void write_file(const std::filesystem::path& p, const std::string& bytes) {
    std::ofstream out(p, std::ios::binary);
    out << bytes;
}

// `size` bytes from a xorshift generator: different per seed, not all text.
inline std::string seeded_bytes(std::uint32_t seed, std::size_t size) {
    std::string s(size, '\0');
    std::uint32_t x = seed ? seed : 1;
    for (auto& c : s) {
        x ^= x << 13;
        x ^= x >> 17;
        x ^= x << 5;
        c = static_cast<char>(x & 0xff);
    }
    return s;
}

}  // namespace umf::test
