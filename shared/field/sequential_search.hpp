// Sequential construction of a 4-orientable field: modules are set in raster
// order; the module that completes a window may only take a value that gives
// the window an unused class. Dead ends backtrack; a search that thrashes in
// one place jumps back a few rows and tries a fresh random continuation.
#pragma once

#include <cstdint>
#include <random>
#include <vector>

#include "shared/field/field.hpp"
#include "shared/field/window_classes.hpp"

namespace umf {

class SequentialSearch {
public:
    SequentialSearch(const Field& shape, const WindowClasses& classes, std::uint64_t seed);

    // Tries up to `attempts` more module values; returns true once the field is complete.
    bool run(std::uint64_t attempts);

    bool complete() const { return depth_ == cells_; }
    bool exhausted() const { return exhausted_; }  // no 4-orientable completion exists
    std::uint64_t attempts() const { return attempts_; }
    std::uint64_t jumps() const { return jumps_; }
    long windows_placed() const { return placed_windows_; }
    long best_windows_placed() const { return best_windows_; }
    long windows_total() const { return windows_total_; }

    // The deepest state reached, with the modules not yet set filled at random:
    // a complete field when complete(), otherwise a field with conflicts.
    Field best_field() const;

private:
    void choose_order(int cell);
    std::uint64_t window_code_ending_at(int cell) const;
    void step_back();
    void jump_back(int cells);

    Field shape_;
    const WindowClasses& classes_;
    ClassSet used_;
    std::mt19937_64 rng_;
    int width_, n_, k_, cells_;
    long windows_total_;

    std::vector<std::uint8_t> grid_;
    std::vector<std::uint8_t> order_;    // k values per cell, in the order to try
    std::vector<std::uint8_t> tried_;    // values of the order tried so far
    std::vector<std::uint64_t> placed_;  // class taken by the window this cell completed, or kNone
    int depth_ = 0;                      // cells set
    long placed_windows_ = 0;
    long best_windows_ = 0;
    std::vector<std::uint8_t> best_grid_;
    int best_depth_ = 0;
    std::uint64_t attempts_ = 0;
    std::uint64_t jumps_ = 0;
    std::uint64_t since_progress_ = 0;
    int frontier_ = 0;  // deepest cell reached since the last jump
    bool exhausted_ = false;
};

}  // namespace umf
