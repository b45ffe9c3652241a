// The order of the search's parts (search_plan.hpp's kPartOrder) judged on
// frames the first scan misses: how long a frame waits to be found in a
// given order, and the greedy order that finds them soonest for the cost.
#pragma once

#include <algorithm>
#include <map>
#include <string>
#include <vector>

#include "shared/detect/search_plan.hpp"

namespace umf::bench {

inline std::string order_text(const std::vector<int>& order) {
    std::string s;
    for (int k : order) s += (s.empty() ? "" : ", ") + std::to_string(k);
    return s;
}

// The frames the first scan misses at one resolution: per frame the parts
// that find it, as bits; and each part's median cost there without the field.
struct PartFinds {
    std::vector<unsigned> found_by;
    std::map<int, double> cost;
};

// The mean time (ms) to find a frame the first scan misses when the parts
// run in `order`: the summed median costs of the parts before the one that
// finds it and its own; a frame no part finds costs them all.
inline double mean_time_to_find(const std::vector<int>& order, const std::vector<PartFinds>& sets) {
    double sum = 0;
    std::size_t frames = 0;
    for (const PartFinds& set : sets)
        for (unsigned mask : set.found_by) {
            ++frames;
            for (int k : order) {
                sum += set.cost.at(k);
                if (mask & (1u << k)) break;
            }
        }
    return frames > 0 ? sum / static_cast<double>(frames) : 0;
}

// The parts in the order that finds the missed frames soonest for their cost,
// over frames of several resolutions: greedy, the part that finds the most
// frames not yet found for the time it adds to all of them next.
inline std::vector<int> greedy_order(std::vector<PartFinds> sets) {
    std::vector<int> order, left;
    for (int k = 0; k < kSearchParts; ++k) left.push_back(k);
    while (!left.empty()) {
        auto best = left.begin();
        double best_rate = -1;
        for (auto it = left.begin(); it != left.end(); ++it) {
            double found = 0, added_ms = 0;
            for (const PartFinds& set : sets) {
                for (unsigned m : set.found_by) found += (m >> *it) & 1u;
                added_ms += static_cast<double>(set.found_by.size()) * set.cost.at(*it);
            }
            const double rate = found / std::max(added_ms, 0.05);
            if (rate > best_rate) best_rate = rate, best = it;
        }
        const int k = *best;
        order.push_back(k);
        left.erase(best);
        for (PartFinds& set : sets)
            set.found_by.erase(std::remove_if(set.found_by.begin(), set.found_by.end(),
                                              [k](unsigned m) { return (m >> k) & 1u; }),
                               set.found_by.end());
    }
    return order;
}

}  // namespace umf::bench
