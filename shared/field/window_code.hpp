// Window codes: an n x n window of a field as one integer, its rotations and
// its canonical form, for module keys and for edge-sign keys.
#pragma once

#include <cstdint>
#include <vector>

#include "shared/field/field.hpp"

namespace umf {

// Codes are base-k digits of the module values (module keys) or base-3 digits
// of the edge signs plus one (edge keys). Digit order for module keys: row-major
// over the window. For edge keys: the n(n-1) horizontal edges sgn(a[i][j+1]-a[i][j])
// row-major, then the n(n-1) vertical edges sgn(a[i+1][j]-a[i][j]) row-major.
class WindowCodec {
public:
    WindowCodec(int window, int colors, WindowKey key);

    int window() const { return n_; }
    int colors() const { return k_; }
    WindowKey key() const { return key_; }
    int digits() const { return static_cast<int>(place_.size()); }
    int base() const { return base_; }
    // Number of distinct codes (base^digits).
    std::uint64_t code_space() const { return space_; }

    // Code of the window whose top-left module is (row, col), turned clockwise
    // by quarter_turns * 90 degrees before coding.
    std::uint64_t code_at(const Field& field, int row, int col, int quarter_turns = 0) const;
    // Code of an n x n window given row-major.
    std::uint64_t code_of(const std::uint8_t* window_values) const;

    // The code of the same window turned clockwise by 90 degrees.
    std::uint64_t rotate(std::uint64_t code) const;
    // Smallest code over the four rotations: windows that are rotations of one
    // another share it.
    std::uint64_t canonical(std::uint64_t code) const;
    // True when the window equals itself turned by 180 (and so possibly 90)
    // degrees: such a window does not tell its orientation.
    bool self_symmetric(std::uint64_t code) const { return rotate(rotate(code)) == code; }

    // Digit d of a code and the code with it changed.
    int digit(std::uint64_t code, int d) const { return static_cast<int>(code / place_[d] % base_); }
    std::uint64_t place(int d) const { return place_[d]; }

private:
    int n_;
    int k_;
    WindowKey key_;
    int base_;
    std::uint64_t space_;
    std::vector<std::uint64_t> place_;    // base^d
    std::vector<int> rot_source_;         // digit d of rotate(c) comes from digit rot_source_[d] of c
    std::vector<bool> rot_negate_;        // ... with its sign flipped (edge keys)
};

}  // namespace umf
