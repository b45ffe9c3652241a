// What the detector read from the image, before it knows where it is: a grid
// of modules in image order (row 0 at the top of the grid the image shows),
// with module values for module-keyed fields and edge signs for edge-keyed
// ones. Anything not read is kUnknown.
#pragma once

#include <cstdint>
#include <optional>
#include <vector>

#include "shared/field/window_code.hpp"

namespace umf {

struct ModuleGrid {
    static constexpr std::int8_t kUnknown = -128;

    int rows = 0;
    int cols = 0;
    std::vector<std::int8_t> value;  // rows * cols module values
    std::vector<std::int8_t> right;  // rows * cols: sign(value(i, j+1) - value(i, j)); last column unused
    std::vector<std::int8_t> down;   // rows * cols: sign(value(i+1, j) - value(i, j)); last row unused

    ModuleGrid() = default;
    ModuleGrid(int rows_, int cols_)
        : rows(rows_),
          cols(cols_),
          value(static_cast<std::size_t>(rows_) * cols_, kUnknown),
          right(value.size(), kUnknown),
          down(value.size(), kUnknown) {}

    std::int8_t& at(int i, int j) { return value[static_cast<std::size_t>(i) * cols + j]; }
    std::int8_t at(int i, int j) const { return value[static_cast<std::size_t>(i) * cols + j]; }
    std::int8_t& right_of(int i, int j) { return right[static_cast<std::size_t>(i) * cols + j]; }
    std::int8_t right_of(int i, int j) const { return right[static_cast<std::size_t>(i) * cols + j]; }
    std::int8_t& below(int i, int j) { return down[static_cast<std::size_t>(i) * cols + j]; }
    std::int8_t below(int i, int j) const { return down[static_cast<std::size_t>(i) * cols + j]; }

    // Edge signs from the module values, where both neighbours are known.
    void derive_edges();

    // The rows x cols part from cell (i0, j0) on; cells outside this grid are unknown.
    ModuleGrid crop(int i0, int j0, int rows, int cols) const;
};

// The code of the n x n window whose top-left grid cell is (i, j), in the
// codec's key, or nothing when a module or edge it needs is unknown.
std::optional<std::uint64_t> observed_code(const ModuleGrid& grid, const WindowCodec& codec, int i, int j);

}  // namespace umf
