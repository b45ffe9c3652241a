// Synthesis of 4-orientable fields.
#pragma once

#include <atomic>
#include <cstdint>
#include <functional>
#include <string>

#include "shared/field/field.hpp"

namespace umf {

struct GeneratorOptions {
    int width = 0;
    int height = 0;
    int window = 4;
    int colors = 2;
    WindowKey key = WindowKey::modules;
    std::uint64_t seed = 1;
    // Independent searches run side by side; the first to finish (counted in
    // rounds, not wall time) wins, so the result depends only on seed and
    // chains, never on the number of cores or their speed.
    int chains = 2;
    int threads = 0;            // 0: one per chain, at most the hardware's cores
    double time_limit_s = 0;    // 0: no limit
    // k-ary fields: module changes tried to raise edge contrast once the field
    // is 4-orientable; -1 chooses 40 per module.
    long contrast_steps = -1;
    std::string id;             // empty: default_field_id() plus "-s<seed>"
};

struct GeneratorProgress {
    double elapsed_s = 0;
    std::uint64_t attempts = 0;     // module values tried, all chains
    double attempts_per_s = 0;
    long windows_total = 0;
    long windows_placed = 0;        // deepest over the chains
    long conflicts_left() const { return windows_total - windows_placed; }
    std::uint64_t jumps = 0;        // restarts of stuck regions, all chains
};

struct GeneratorResult {
    Field field;           // 4-orientable when complete
    bool complete = false;
    bool stopped = false;  // by the stop flag
    bool timed_out = false;
    double seconds = 0;
    std::uint64_t attempts = 0;
    int winning_chain = -1;
};

using ProgressCallback = std::function<void(const GeneratorProgress&)>;

// Throws std::invalid_argument for impossible requests (sizes, window, colours,
// more windows than the counting bound allows).
GeneratorResult generate_field(const GeneratorOptions& options, const ProgressCallback& progress = {},
                               const std::atomic<bool>* stop = nullptr);

}  // namespace umf
