// Which of a frame's searches Detector::detect runs. A photo on its own gets
// all of them (full_search): the first scan at the frame's own size (the
// part around the aim first, then the whole frame, at half size where the
// frame is large), then,
// while nothing is found, the other parts in the order that finds a field
// soonest for their cost (the rescans, the smaller sizes, the lattice,
// double size and the frame smoothed), and a second pass over the grid-line
// labellings the first one left. Together they cost a frame without the
// field about 29 ms at 640 x 480 (median; 55 ms p95; umf_speed_benchmark,
// 2026-12-04), where the first scan alone costs about 1.2 ms. A video does
// not need every frame to try everything: a tracker may give each frame
// without a lock a share of the
// search (search_share; TrackerOptions::spread_search): the first scan's
// first pairs of labellings and as many pieces of the other parts as fit in
// a budget, so that no frame stalls the camera and a field that only another
// part finds is found within a round of frames.
#pragma once

#include <array>
#include <cstddef>
#include <limits>

namespace umf {

// The scans at the frame's own size (Detector's step 1), as bits.
inline constexpr unsigned kFirstScan = 1u;         // the sparse scanlines
inline constexpr unsigned kNoisyScan = 2u;         // three pixels wide, in a noisy frame
inline constexpr unsigned kFirstDenserScan = 4u;   // the lines half way between; each next bit halves again
inline constexpr unsigned kEveryScan = ~0u;

// The sets of a scan's edgels searched (Detector's search_edgel_sets),
// as bits: all of them, the field-like ones alone, those off thin lines.
// The field-like ones are searched first.
inline constexpr unsigned kAllEdgels = 1u;
inline constexpr unsigned kFieldLikeEdgels = 2u;
inline constexpr unsigned kOffThinLineEdgels = 4u;
inline constexpr unsigned kEveryEdgelSet = 7u;

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
    // Of every scan above: its edgel sets searched, and whether its
    // searches' later pairs of labellings are tried in the second pass,
    // after the first pass's likeliest few
    // (DetectorOptions::first_pass_pairs) of every search.
    unsigned edgel_sets = kEveryEdgelSet;
    bool second_pass = true;
    // The lattice at the frame's own size before the first scan's searches
    // when that scan's edgels say the modules are small
    // (modules_look_small); part 1 then does not run it again.
    bool lattice_first_if_small = false;
    // The first scan made and searched first on the part of the frame
    // around the aim alone (DetectorOptions::near_aim_part), with the whole
    // frame's scanline step, then on the whole frame: a quarter of the
    // edgels and of the modules to read and refit, where the field nearly
    // always fills the middle of the view.
    bool near_aim_first = false;
    // With near_aim_first: the first scan on that part alone, not on the
    // whole frame (a frame whose time a held search gives to the round).
    bool near_aim_alone = false;
    // With near_aim_first: the first scan of the whole frame at half size
    // where the frame is large (DetectorOptions::whole_frame_half_min_side).
    bool whole_frame_halved = false;
    // With near_aim_first: the whole frame's first scan searches its
    // field-like edgels and not all of them after, where the field-like ones
    // were few enough among the others to be searched apart
    // (Detector::search_edgel_sets). All edgels' grids there are mostly the
    // content's: on the tuning set's frames without the field at 640 x 480
    // that search was half the first scan's time, and it found one frame
    // with the field of 264 (docs/BENCHMARKS.md, "the whole frame's field-like
    // edgels alone").
    bool whole_frame_field_like_alone = false;
};

// A search held to a time limit (a tracker's spread search with
// TrackerOptions::frame_ms), taken up on the next frame where it stopped.
// A plan's steps are the searches of its scans' edgel sets and its
// lattices, one per set or lattice it names, counted whether or not the
// set has enough edgels to be searched, so that the same plan on the next
// frame counts the same steps. The first plan (spread_first(), run on
// every frame) runs whole unless held (below); of the later plans' steps
// the first `min_steps` run whatever the time, and after them no step
// starts that would end more than `ms` after the call began, each taken to
// cost what the call's steps so far cost on average, or with
// `as_dear_as_dearest` as much as the dearest of them (the same frame's
// content makes them dear or cheap; the average let one frame in twenty
// end a millisecond late); the images and scans of a step not started are
// not made. The first `skip_steps` of the second plan are not run again
// (an earlier frame searched them). A step that has started runs to its
// end: a search stopped half way would lose what its other half finds.
//
// The first plan's steps after its first `first_min_steps` may be held too
// (by default none are), to `first_ms` where that is given (a tracker's
// whole time between two camera frames, where `ms` is its search's share):
// they are then the first steps `min_steps` counts, those before
// `first_skip_steps` are not run again (an earlier frame searched them), and
// a first plan cut short ends the call.
struct SearchLimit {
    double ms = 0;
    int min_steps = 0;
    int skip_steps = 0;
    int first_min_steps = std::numeric_limits<int>::max();
    int first_skip_steps = 0;
    double first_ms = 0;
    bool as_dear_as_dearest = false;
    // What the call did: the later plans it ran to their end, the steps of
    // the next one it reached (skipped ones included) when it stopped, the
    // steps it ran, and the plan and step that found the field (-1: none);
    // where the first plan stopped (skipped steps included; 0: it ran to
    // its end) and the steps of it held to the time that ran.
    int plans_done = 0;
    int steps_into_next = 0;
    int steps_run = 0;
    int found_plan = -1;
    int found_step = -1;
    int first_steps_into_next = 0;
    int first_held_steps_run = 0;
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

// A part's pieces, for a search spread thinner still: piece 0 its searches
// over the field-like edgels (and its lattice, if any), piece 1 over all
// edgels and those off thin lines, both with their first pairs of
// labellings only (a spread search leaves the later pairs out: on the
// tuning set they found no frame the first pairs of another piece did not,
// and made the round half as long again). Each costs a frame without the
// field a fraction of the part.
inline constexpr int kPiecesOfAPart = 2;
constexpr SearchPlan search_piece(SearchPlan part, int piece) {
    part.edgel_sets = piece == 0 ? kFieldLikeEdgels : (kAllEdgels | kOffThinLineEdgels);
    if (piece != 0) part.lattices = 0;
    part.second_pass = false;
    return part;
}

// The order the parts run in, in a photo's search and in the schedule: by
// how soon they find the tuning set's frames the first scan misses for what
// they cost on frames without the field (umf_speed_benchmark --parts, which
// prints the greedy order: most frames not yet found per millisecond next),
// so that a frame a cheap part finds does not first pay for the dear ones.
// Since the lattice costs half what it did (2026-12-04: at 640 x 480 part 1
// 0.65 ms, 3 0.66, 8 (at 1280 x 720) 0.69, where the first scan costs 1.2),
// its three parts come first: the modelled mean time to find a frame the
// first scan misses, 5.4 ms in the order before, 4.6 in this one.
inline constexpr std::array<int, kSearchParts> kPartOrder = {8, 1, 3, 0, 2, 10, 4, 9, 5, 6, 7, 11};

// A photo's search: the first scan, then the parts in order while nothing
// is found (Detector::detect over the plans). Its first scan searches a
// large frame's whole frame at half size (SearchPlan::whole_frame_halved)
// unless `whole_frame_halved` is false.
using FullSearch = std::array<SearchPlan, kSearchParts + 1>;
constexpr FullSearch full_search(const std::array<int, kSearchParts>& order = kPartOrder,
                                 bool whole_frame_halved = true) {
    FullSearch plans{};
    plans[0] = first_scan_only();
    plans[0].lattice_first_if_small = true;
    plans[0].near_aim_first = true;
    plans[0].whole_frame_halved = whole_frame_halved;
    plans[0].whole_frame_field_like_alone = true;
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
inline constexpr std::array<int, kSearchParts> kPartOrderNearPrior = {2, 7, 8, 1, 3, 0, 10, 4, 9, 5, 6, 11};

// Whether a part searches edgels at all (the others are lattices alone).
constexpr bool searches_edgels(const SearchPlan& p) {
    return (p.scans | p.smaller_scans | p.double_scans | p.smoothed_scans | p.smoothed_smaller_scans) != 0;
}

// One piece of the spread search's round: `piece` (search_piece) of `part`
// (search_part) and what it costs a frame without the field, in ms at 640 x
// 480: the median over the tuning set's frames without the field of the
// piece run alone, its scans and images made for it alone (less where a
// share's pieces share them).
struct SearchPiece {
    int part = 0;
    int piece = 0;
    double cost = 0;
    constexpr SearchPlan plan() const { return search_piece(search_part(part), piece); }
};

// Each piece's cost, by part and piece (0 for a piece a lattice part does
// not have). Part 8, the lattice below half size, runs only on larger
// frames: about a quarter of part 3 there. The lattice parts' costs (1, 3,
// 8) are from before the lattice took half the time (2026-12-04): the
// shares a fixed budget makes were judged with these figures and are kept
// until they are judged again with the new ones.
inline constexpr double kPieceCost[kSearchParts][kPiecesOfAPart] = {
    {0.46, 0.78}, {1.33, 0}, {1.09, 1.73}, {1.45, 0},    {0.81, 1.53}, {1.37, 1.73},
    {0.96, 1.16}, {1.73, 2.83}, {0.40, 0}, {3.03, 4.50}, {2.22, 3.15}, {2.09, 3.21}};

// What a frame of a search spread over a video's frames runs before its
// share of the round: the first scan's first pairs over every edgel set
// (its pieces 0 and 1; the whole frame's all edgels only where its
// field-like ones are not searched apart, whole_frame_field_like_alone). A
// ruled page's field is found by the edgels off its rules; with them a
// round away, a tracker on such a page lost most of its frames (the tuning
// set's ruled video at opacity 0.1, 640 x 480: 39 of 40 found with every
// search, 14 with them in the round). A far
// screen's small modules send it to the lattice first, as in a photo's
// search: the lattice's share is a round away (the held-out set's far views
// at 640 x 480, tracked: 19 of 40 found without the cue, 31 with it). A
// frame held to its time with the first scan held too runs its search of
// the part around the aim whatever the time and its searches of the whole
// frame while they fit, taken up on the next frame where they stopped
// (SearchLimit's first_min_steps; TrackerOptions::hold_first_scan): on
// content dense with edges they alone cost a frame without the field up to
// 4 ms at 640 x 480.
constexpr SearchPlan spread_first() {
    SearchPlan p = first_scan_only();
    p.second_pass = false;
    p.lattice_first_if_small = true;
    p.near_aim_first = true;
    p.whole_frame_halved = true;
    p.whole_frame_field_like_alone = true;
    return p;
}

// The round of a search spread over a video's frames: every part's piece 0
// in kPartOrder's order, where most of what the parts find is found; then
// every part's piece 1.
constexpr int round_pieces() {
    int n = 0;
    for (int part = 0; part < kSearchParts; ++part) n += searches_edgels(search_part(part)) ? kPiecesOfAPart : 1;
    return n;
}
inline constexpr int kRoundPieces = round_pieces();
constexpr std::array<SearchPiece, kRoundPieces> spread_round() {
    std::array<SearchPiece, kRoundPieces> round{};
    std::size_t n = 0;
    for (int piece = 0; piece < kPiecesOfAPart; ++piece)
        for (const int part : kPartOrder)
            if (piece == 0 || searches_edgels(search_part(part))) round[n++] = {part, piece, kPieceCost[part][piece]};
    return round;
}
inline constexpr std::array<SearchPiece, kRoundPieces> kSpreadRound = spread_round();

// One frame's share of the spread search: spread_first(), then `pieces`
// consecutive pieces of the round from `first_piece`.
struct ScheduledSearch {
    std::array<SearchPlan, kRoundPieces + 1> plans{};
    std::size_t count = 0;
    int first_piece = 0;
    int pieces = 0;
};

// The share from `first_piece` on: as many pieces as fit in `budget` (their
// costs summed, at least one piece, at most `max_pieces`), never past the
// round's end.
constexpr ScheduledSearch search_share(int first_piece, double budget, int max_pieces = kRoundPieces) {
    ScheduledSearch out;
    out.first_piece = ((first_piece % kRoundPieces) + kRoundPieces) % kRoundPieces;
    out.plans[out.count++] = spread_first();
    double spent = 0;
    for (int at = out.first_piece; at < kRoundPieces && out.pieces < max_pieces; ++at) {
        const SearchPiece& piece = kSpreadRound[static_cast<std::size_t>(at)];
        if (out.pieces > 0 && spent + piece.cost > budget) break;
        spent += piece.cost;
        out.plans[out.count++] = piece.plan();
        ++out.pieces;
    }
    return out;
}

// The frames of one round with this budget: shares one after the other
// from the round's start.
constexpr int schedule_frames(double budget) {
    int frames = 0;
    for (int at = 0; at < kRoundPieces; at += search_share(at, budget).pieces) ++frames;
    return frames;
}

// The search of the k-th consecutive frame without a lock with a budget
// that stays the same: spread_first(), then the k-th share of the round,
// round after round. A frame pays for spread_first() (about 1 ms) and
// `budget` at 640 x 480 (a piece costs less in a share than alone, where it makes
// the scans and images it shares with others).
constexpr ScheduledSearch search_schedule(int k, double budget) {
    const int frames = schedule_frames(budget);
    const int g = ((k % frames) + frames) % frames;
    int at = 0;
    for (int i = 0; i < g; ++i) at += search_share(at, budget).pieces;
    return search_share(at, budget);
}

}  // namespace umf
