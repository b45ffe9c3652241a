// Small helpers shared by the field tests.
#pragma once

#include <random>
#include <string>

#include "shared/field/field.hpp"

namespace umf::test {

inline Field random_field(int width, int height, int window, int colors, std::uint32_t seed,
                          WindowKey key = WindowKey::modules) {
    Field f = make_field(width, height, window, colors, key);
    std::mt19937 rng(seed);
    for (auto& m : f.modules) m = static_cast<std::uint8_t>(rng() % colors);
    return f;
}

inline std::string data_path(const std::string& name) { return std::string(UMF_TEST_DATA_DIR) + "/" + name; }

}  // namespace umf::test
