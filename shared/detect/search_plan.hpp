// Which of a frame's searches Detector::detect runs. A photo on its own gets
// all of them (full_search): the first scan at the frame's own size, then,
// while nothing is found, the other parts in the order that finds a field
// soonest for their cost (the rescans, the smaller sizes, the lattice,
// double size and the frame smoothed), and a second pass over the grid-line
// labellings the first one left. Together they cost a frame without the
// field about 40 ms at 640 x 480 (median; 80 ms p95), where the first scan
// alone costs about 1.3 ms. A video does not need every frame to try
// everything: a tracker may give each frame without a lock a share of the
// search (search_schedule; TrackerOptions::spread_search): the first scan
// and as many other parts as fit in a budget, so that no frame stalls
// the camera and a field that only another part finds is found within a
// round of a few frames.
#pragma once

#include <array>
#include <cstddef>

namespace umf {

// The scans at the frame's own size (Detector's step 1), as bits.
inline constexpr unsigned kFirstScan = 1u;         // the sparse scanlines
inline constexpr unsigned kNoisyScan = 2u;         // three pixels wide, in a noisy frame
inline constexpr unsigned kFirstDenserScan = 4u;   // the lines half way between; each next bit halves again
inline constexpr unsigned kEveryScan = ~0u;

// The parts of the search; each scan mask names the scans searched at that
// size (a mask of 0 leaves the size out, its resizing too).
struct SearchPlan {
    unsigned scans = kEveryScan;           // at the frame's own size
    unsigned smaller_scans = kEveryScan;   // at half size and below (DetectorOptions::half_size_min_side)
    // The lattice around the aim (DetectorOptions::lattice_enabled): bit 0
    // at the frame's own size, bit 1 at half size, bit 2 a quarter, ...
    unsigned lattices = ~0u;
    unsigned double_scans = kEveryScan;    // around the aim at twice the size (DetectorOptions::double_size_max_side)
    unsigned smoothed_scans = kEveryScan;  // the frame smoothed (DetectorOptions::smoothed_search), its own size
    unsigned smoothed_smaller_scans = kEveryScan;  // and below
};

// The first scan at the frame's own size and nothing else.
constexpr SearchPlan first_scan_only() { return {kFirstScan, 0, 0, 0, 0, 0}; }

// The parts of the search besides the first scan, by number (the numbers
// umf_speed_benchmark --parts reports): 0 half size's first scan (and a
// quarter's), 1 the lattice at the frame's size, 2 the noisy scan and the
// first denser one, 3 the lattice at half size, 4 half size's other scans,
// 5 the frame smoothed, its first scan, 6 double size's first scan, 7 the
// denser scans after the first, 8 the lattice below half size, 9 the frame
// smoothed, its other scans, 10 double size's other scans, 11 the frame
// smoothed at smaller sizes.
constexpr SearchPlan search_part(int part) {
    constexpr unsigned kRescans = kEveryScan & ~kFirstScan;
    constexpr unsigned kLaterDenserScans = kEveryScan & ~(kFirstScan | kNoisyScan | kFirstDenserScan);
    SearchPlan p{0, 0, 0, 0, 0, 0};
    switch (part) {
        case 0: p.smaller_scans = kFirstScan; break;
        case 1: p.lattices = 1u; break;
        case 2: p.scans = kNoisyScan | kFirstDenserScan; break;
        case 3: p.lattices = 2u; break;
        case 4: p.smaller_scans = kRescans; break;
        case 5: p.smoothed_scans = kFirstScan; break;
        case 6: p.double_scans = kFirstScan; break;
        case 7: p.scans = kLaterDenserScans; break;
        case 8: p.lattices = ~3u; break;
        case 9: p.smoothed_scans = kRescans; break;
        case 10: p.double_scans = kRescans; break;
        default: p.smoothed_smaller_scans = kEveryScan; break;
    }
    return p;
}
inline constexpr int kSearchParts = 12;

// The order the parts run in, in a photo's search and in the schedule: by
// how soon they find the tuning set's frames the first scan misses for what
// they cost on frames without the field (umf_speed_benchmark --parts, which
// prints the greedy order: most frames not yet found per millisecond next),
// so that a frame a cheap part finds does not first pay for the dear ones.
inline constexpr std::array<int, kSearchParts> kPartOrder = {0, 6, 1, 8, 2, 10, 4, 3, 11, 9, 5, 7};

// A photo's search: the first scan, then the parts in order while nothing
// is found (Detector::detect over the plans).
using FullSearch = std::array<SearchPlan, kSearchParts + 1>;
constexpr FullSearch full_search(const std::array<int, kSearchParts>& order = kPartOrder) {
    FullSearch plans{};
    plans[0] = first_scan_only();
    for (std::size_t k = 0; k < order.size(); ++k) plans[k + 1] = search_part(order[k]);
    return plans;
}

// The order when there is a prior (a tracker that lost its lock a few frames
// ago): the frame's own size first (parts 2 and 7), as the tracker takes no
// motion from a place found at another size and follows a coarser map less
// well, then the others as kPartOrder has them. In kPartOrder's order a
// tracker in a dim room kept finding the field at half size and searched
// nearly every frame anew (tuning set, opacity 0.1, 1280 x 720: low_light
// 1.07 ms median a frame before, 24.7 ms).
inline constexpr std::array<int, kSearchParts> kPartOrderNearPrior = {2, 7, 0, 6, 1, 8, 10, 4, 3, 11, 9, 5};

// What each part costs a frame without the field, one against another: the
// medians of `umf_speed_benchmark --parts` at 640 x 480, in ms (part 8, the
// lattice below half size, runs only on larger frames; about a quarter of
// part 3 there).
inline constexpr std::array<double, kSearchParts> kPartCost = {1.00, 3.16, 3.26, 3.19, 2.21, 1.87,
                                                               1.47, 5.40, 0.80, 6.44, 6.35, 4.12};

// One frame's share of a search spread over a video's frames: the first scan,
// then parts in kPartOrder's order.
struct ScheduledSearch {
    std::array<SearchPlan, kSearchParts + 1> plans{};
    std::size_t count = 0;
};

// The round of the schedule: kPartOrder cut into consecutive groups, each
// as many parts as fit in `budget` (their kPartCost summed, at least one
// part a group). Returns the number of groups; starts[g] is where group g
// begins in kPartOrder, starts[groups] its end.
constexpr int schedule_groups(double budget, std::array<int, kSearchParts + 1>& starts) {
    int groups = 0, at = 0;
    while (at < kSearchParts) {
        starts[static_cast<std::size_t>(groups++)] = at;
        double spent = kPartCost[static_cast<std::size_t>(kPartOrder[static_cast<std::size_t>(at)])];
        ++at;
        while (at < kSearchParts &&
               spent + kPartCost[static_cast<std::size_t>(kPartOrder[static_cast<std::size_t>(at)])] <= budget)
            spent += kPartCost[static_cast<std::size_t>(kPartOrder[static_cast<std::size_t>(at++)])];
    }
    starts[static_cast<std::size_t>(groups)] = kSearchParts;
    return groups;
}

// The frames of one round of the schedule with this budget.
constexpr int schedule_frames(double budget) {
    std::array<int, kSearchParts + 1> starts{};
    return schedule_groups(budget, starts);
}

// The search of the k-th consecutive frame without a lock: the first scan,
// then the k-th group of parts of the round, round after round. A part the
// field needs comes every few frames, and a frame pays for the first scan
// and about `budget` (nominally 1.3 + 8 ms at 640 x 480 for a budget of 8,
// against about 40 ms for the whole search; more where the share's second
// pass over the labellings its plans left is long: 31 ms p95 on the tuning
// frames without the field).
constexpr ScheduledSearch search_schedule(int k, double budget) {
    std::array<int, kSearchParts + 1> starts{};
    const int groups = schedule_groups(budget, starts);
    const int g = ((k % groups) + groups) % groups;
    ScheduledSearch out;
    out.plans[out.count++] = first_scan_only();
    for (int at = starts[static_cast<std::size_t>(g)]; at < starts[static_cast<std::size_t>(g) + 1]; ++at)
        out.plans[out.count++] = search_part(kPartOrder[static_cast<std::size_t>(at)]);
    return out;
}

}  // namespace umf
