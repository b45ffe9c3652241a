#include "shared/field/window_code.hpp"

#include <algorithm>
#include <stdexcept>
#include <string>

namespace umf {

namespace {

int sign(int v) { return (v > 0) - (v < 0); }

// Module (i, j) of a window turned clockwise by a quarter turn shows module
// (n-1-j, i) of the original.
void source_of_turned(int n, int i, int j, int& si, int& sj) {
    si = n - 1 - j;
    sj = i;
}

}  // namespace

WindowCodec::WindowCodec(int window, int colors, WindowKey key) : n_(window), k_(colors), key_(key) {
    if (n_ < 2 || n_ > 4) throw std::invalid_argument("window must be 2..4, not " + std::to_string(n_));
    if (k_ < 2 || k_ > kMaxColors) throw std::invalid_argument("colors must be 2.." + std::to_string(kMaxColors));
    base_ = key_ == WindowKey::modules ? k_ : 3;
    int digits = key_ == WindowKey::modules ? n_ * n_ : 2 * n_ * (n_ - 1);
    place_.resize(digits);
    std::uint64_t p = 1;
    for (int d = 0; d < digits; ++d) {
        place_[d] = p;
        p *= static_cast<std::uint64_t>(base_);
    }
    space_ = p;

    rot_source_.assign(digits, 0);
    rot_negate_.assign(digits, false);
    if (key_ == WindowKey::modules) {
        for (int i = 0; i < n_; ++i)
            for (int j = 0; j < n_; ++j) {
                int si, sj;
                source_of_turned(n_, i, j, si, sj);
                rot_source_[i * n_ + j] = si * n_ + sj;
            }
        return;
    }
    // An edge joins two modules; after the turn it joins their images. Find
    // the original edge between the two source modules and whether its
    // direction (left->right or top->bottom) is reversed.
    const int h_edges = n_ * (n_ - 1);
    auto edge_index = [&](int i0, int j0, int i1, int j1, bool& reversed) {
        if (i0 == i1) {  // horizontal neighbours
            int j = std::min(j0, j1);
            reversed = j1 < j0;
            return i0 * (n_ - 1) + j;
        }
        int i = std::min(i0, i1);
        reversed = i1 < i0;
        return h_edges + i * n_ + j0;
    };
    for (int d = 0; d < digits; ++d) {
        int a_i, a_j, b_i, b_j;
        if (d < h_edges) {
            a_i = d / (n_ - 1);
            a_j = d % (n_ - 1);
            b_i = a_i;
            b_j = a_j + 1;
        } else {
            a_i = (d - h_edges) / n_;
            a_j = (d - h_edges) % n_;
            b_i = a_i + 1;
            b_j = a_j;
        }
        int sa_i, sa_j, sb_i, sb_j;
        source_of_turned(n_, a_i, a_j, sa_i, sa_j);
        source_of_turned(n_, b_i, b_j, sb_i, sb_j);
        bool reversed = false;
        rot_source_[d] = edge_index(sa_i, sa_j, sb_i, sb_j, reversed);
        rot_negate_[d] = reversed;
    }
}

std::uint64_t WindowCodec::code_of(const std::uint8_t* w) const {
    std::uint64_t code = 0;
    if (key_ == WindowKey::modules) {
        for (int d = 0; d < n_ * n_; ++d) code += w[d] * place_[d];
        return code;
    }
    int d = 0;
    for (int i = 0; i < n_; ++i)
        for (int j = 0; j + 1 < n_; ++j, ++d) code += (sign(w[i * n_ + j + 1] - w[i * n_ + j]) + 1) * place_[d];
    for (int i = 0; i + 1 < n_; ++i)
        for (int j = 0; j < n_; ++j, ++d) code += (sign(w[(i + 1) * n_ + j] - w[i * n_ + j]) + 1) * place_[d];
    return code;
}

std::uint64_t WindowCodec::code_at(const Field& field, int row, int col, int quarter_turns) const {
    std::uint8_t w[16];
    for (int i = 0; i < n_; ++i)
        for (int j = 0; j < n_; ++j) w[i * n_ + j] = field.at(row + i, col + j);
    // Turn the window itself, so the verifier's codes do not depend on rotate().
    for (int t = 0; t < (quarter_turns & 3); ++t) {
        std::uint8_t turned[16];
        for (int i = 0; i < n_; ++i)
            for (int j = 0; j < n_; ++j) {
                int si, sj;
                source_of_turned(n_, i, j, si, sj);
                turned[i * n_ + j] = w[si * n_ + sj];
            }
        std::copy(turned, turned + n_ * n_, w);
    }
    return code_of(w);
}

std::uint64_t WindowCodec::rotate(std::uint64_t code) const {
    std::uint64_t out = 0;
    for (int d = 0; d < digits(); ++d) {
        int v = digit(code, rot_source_[d]);
        if (rot_negate_[d]) v = 2 - v;
        out += static_cast<std::uint64_t>(v) * place_[d];
    }
    return out;
}

std::uint64_t WindowCodec::canonical(std::uint64_t code) const {
    std::uint64_t best = code, c = code;
    for (int t = 1; t < 4; ++t) {
        c = rotate(c);
        best = std::min(best, c);
    }
    return best;
}

}  // namespace umf
