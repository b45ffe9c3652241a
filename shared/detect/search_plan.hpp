// Which of a frame's searches Detector::detect runs. A photo on its own gets
// all of them: the first scan at the frame's own size, then, while nothing is
// found, the rescans, the smaller sizes, the lattice, double size and the
// frame smoothed, and a second pass over the grid-line labellings the first
// one left. Together they cost a frame without the field about 40 ms at
// 640 x 480 (median; 80 ms p95), where the first scan alone costs about 1 ms. A video does not
// need every frame to try everything: a tracker may give each frame without a
// lock one part of the search (search_schedule; TrackerOptions::spread_search),
// the first scan every other frame and one fallback in between, so that no
// frame stalls the camera and a field that only a fallback finds is found
// within a round of frames.
#pragma once

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
    bool second_pass = true;               // the labelling pairs the first pass left (DetectorOptions::first_pass_pairs)
};

// Every search: what a single photo gets.
inline SearchPlan full_search() { return {}; }

// The first scan at the frame's own size and nothing else.
inline SearchPlan first_scan_only() { return {kFirstScan, 0, 0, 0, 0, 0, true}; }

// The fallbacks in the order the schedule tries them: by how many of the
// tuning frames the first scan misses each one finds, at opacity 0.1 and 0.3,
// for what it costs on a frame without the field.
inline SearchPlan search_part(int part) {
    constexpr unsigned kRescans = kEveryScan & ~kFirstScan;
    constexpr unsigned kLaterDenserScans = kEveryScan & ~(kFirstScan | kNoisyScan | kFirstDenserScan);
    SearchPlan p{0, 0, 0, 0, 0, 0, true};
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

// The frames of one round of the schedule.
inline constexpr int kSearchScheduleFrames = 2 * kSearchParts;

// The search of the k-th consecutive frame without a lock: the first scan on
// even frames, the fallbacks in turn on odd ones, round after round. Trying a
// fallback beside the first scan on every frame would find a field that only
// a fallback finds in half the frames, at about twice the cost of a frame
// without the field (4.1 ms against 1.6 ms, median, 640 x 480).
inline SearchPlan search_schedule(int k) {
    k = ((k % kSearchScheduleFrames) + kSearchScheduleFrames) % kSearchScheduleFrames;
    return k % 2 == 1 ? search_part(k / 2) : first_scan_only();
}

}  // namespace umf
