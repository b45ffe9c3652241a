#include "shared/field/sequential_search.hpp"

#include <algorithm>
#include <limits>

namespace umf {

namespace {
constexpr std::uint64_t kNone = std::numeric_limits<std::uint64_t>::max();
}

SequentialSearch::SequentialSearch(const Field& shape, const WindowClasses& classes, std::uint64_t seed)
    : shape_(shape),
      classes_(classes),
      used_(classes.codec().code_space()),
      rng_(seed),
      width_(shape.width),
      n_(shape.window),
      k_(shape.colors),
      cells_(shape.width * shape.height),
      windows_total_(shape.window_count()),
      grid_(cells_, 0),
      order_(static_cast<std::size_t>(cells_) * shape.colors, 0),
      tried_(cells_, 0),
      placed_(cells_, kNone),
      best_grid_(cells_, 0) {}

void SequentialSearch::choose_order(int cell) {
    std::uint8_t* order = &order_[static_cast<std::size_t>(cell) * k_];
    if (k_ == 2) {
        std::uint8_t first = static_cast<std::uint8_t>(rng_() & 1u);
        order[0] = first;
        order[1] = first ^ 1u;
        return;
    }
    // k-ary: avoid flat edges to the left and upper neighbours and lean
    // towards large steps, but keep the order mostly random: a strong
    // preference collapses the field into a checkerboard of few distinct
    // windows. The contrast polish raises contrast afterwards.
    const int r = cell / width_, c = cell % width_;
    std::uniform_real_distribution<double> jitter(0.0, 1.0);
    std::pair<double, int> scored[kMaxColors];
    for (int v = 0; v < k_; ++v) {
        double s = jitter(rng_);
        auto add = [&](int neighbour) {
            int d = v > neighbour ? v - neighbour : neighbour - v;
            s += d == 0 ? -4.0 : 0.25 * d / (k_ - 1);
        };
        if (c > 0) add(grid_[cell - 1]);
        if (r > 0) add(grid_[cell - width_]);
        scored[v] = {-s, v};
    }
    // Insertion sort: k is at most 10.
    for (int i = 1; i < k_; ++i)
        for (int j = i; j > 0 && scored[j] < scored[j - 1]; --j) std::swap(scored[j], scored[j - 1]);
    for (int v = 0; v < k_; ++v) order[v] = static_cast<std::uint8_t>(scored[v].second);
}

std::uint64_t SequentialSearch::window_code_ending_at(int cell) const {
    const int r0 = cell / width_ - n_ + 1, c0 = cell % width_ - n_ + 1;
    std::uint8_t w[16];
    for (int i = 0; i < n_; ++i)
        for (int j = 0; j < n_; ++j) w[i * n_ + j] = grid_[(r0 + i) * width_ + c0 + j];
    return classes_.codec().code_of(w);
}

// Undo the last set module so its next value can be tried.
void SequentialSearch::step_back() {
    --depth_;
    if (placed_[depth_] != kNone) {
        used_.erase(placed_[depth_]);
        placed_[depth_] = kNone;
        --placed_windows_;
    }
}

void SequentialSearch::jump_back(int cells) {
    // Forget the value orders beyond the new depth so the continuation is new.
    int target = std::max(0, depth_ - cells);
    tried_[depth_ < cells_ ? depth_ : cells_ - 1] = 0;
    while (depth_ > target) {
        step_back();
        tried_[depth_] = 0;
    }
    frontier_ = depth_;
    since_progress_ = 0;
    ++jumps_;
}

bool SequentialSearch::run(std::uint64_t budget) {
    // A search stuck this long below its frontier is re-rolling the same few
    // rows; starting them afresh is cheaper than exhausting them.
    const std::uint64_t stall_limit = 64ull * width_;
    const std::uint64_t end = attempts_ + budget;
    while (depth_ < cells_ && attempts_ < end) {
        const int cell = depth_;
        if (tried_[cell] == 0) choose_order(cell);
        if (tried_[cell] == k_) {
            tried_[cell] = 0;
            if (depth_ == 0) {
                exhausted_ = true;
                return false;
            }
            step_back();
            if (++since_progress_ > stall_limit) jump_back(width_ * (1 + static_cast<int>(rng_() % 3)));
            continue;
        }
        const std::uint8_t v = order_[static_cast<std::size_t>(cell) * k_ + tried_[cell]++];
        ++attempts_;
        grid_[cell] = v;
        const int r = cell / width_, c = cell % width_;
        if (r >= n_ - 1 && c >= n_ - 1) {
            auto cls = classes_.of(window_code_ending_at(cell));
            if (cls.self_symmetric || used_.contains(cls.id)) continue;
            used_.insert(cls.id);
            placed_[cell] = cls.id;
            ++placed_windows_;
        }
        ++depth_;
        if (depth_ < cells_) tried_[depth_] = 0;
        if (depth_ > frontier_) {
            frontier_ = depth_;
            since_progress_ = 0;
        }
        if (depth_ > best_depth_) {
            best_depth_ = depth_;
            best_windows_ = placed_windows_;
            std::copy(grid_.begin(), grid_.begin() + depth_, best_grid_.begin());
        }
    }
    return complete();
}

Field SequentialSearch::best_field() const {
    Field f = shape_;
    f.modules.assign(best_grid_.begin(), best_grid_.end());
    std::mt19937_64 fill(best_depth_);
    for (int i = best_depth_; i < cells_; ++i) f.modules[i] = static_cast<std::uint8_t>(fill() % k_);
    return f;
}

}  // namespace umf
