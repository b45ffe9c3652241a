// The search for the field in a single frame (step 1 and the order of the
// searches): scans at the frame's size and smaller ones, the lattice,
// double size, the frame smoothed, each scan's edgels and subsets of them,
// and a search held to a time. Steps 2 to 4, from a scan's edgels to the
// grids read, are in detector_grids.cpp; steps 5 to 8, from a grid to a
// confirmed place, in detector.cpp.
#include <Eigen/Geometry>
#include <algorithm>
#include <chrono>
#include <cmath>
#include <deque>
#include <limits>
#include <optional>

#include "shared/detect/detector.hpp"
#include "shared/detect/field_edgels.hpp"
#include "shared/detect/stage_time.hpp"

namespace umf {

namespace {

// Grey levels of pixel noise above which scanlines are read three pixels wide
// when a first search failed (a phone's camera in dim light).
constexpr double kNoisyImage = 3.0;

// The frame at another size: `scale` times it, from `origin` on. The map
// into it, a prior carried there, and a place found there carried back.
struct Resizing {
    Eigen::Matrix3d to_resized;
    double scale;
    std::optional<DetectionPrior> prior;

    Resizing(double s, const Eigen::Vector2d& origin, const DetectionPrior* frame_prior) : scale(s) {
        to_resized << s, 0, -s * origin.x(), 0, s, -s * origin.y(), 0, 0, 1;
        if (frame_prior)
            prior = DetectionPrior{frame_prior->image_to_field * to_resized.inverse(), frame_prior->radius_modules};
    }
    const DetectionPrior* resized_prior() const { return prior ? &*prior : nullptr; }
    Eigen::Vector2d resized(const Eigen::Vector2d& point) const { return (to_resized * point.homogeneous()).head<2>(); }
    void carry_back(Detection& out, const Eigen::Vector2d& aim) const {
        out.image_to_field = out.image_to_field * to_resized;
        out.aim_image = aim;
        out.size_scale *= scale;
    }
};

// The part of `image` around `aim`, `fraction` of its width and height (8
// pixels at least), kept within the image: a view of its pixels and its
// corner. None where it does not fit (an image of a few pixels).
struct ImagePart {
    GreyView view;
    Eigen::Vector2d origin;
};
std::optional<ImagePart> part_around(const GreyView& im, const Eigen::Vector2d& aim, double fraction) {
    const int w = std::max(8, static_cast<int>(std::lround(im.width * fraction)));
    const int h = std::max(8, static_cast<int>(std::lround(im.height * fraction)));
    if (w > im.width || h > im.height) return std::nullopt;
    const int x0 = std::clamp(static_cast<int>(std::lround(aim.x() - w / 2.0)), 0, im.width - w);
    const int y0 = std::clamp(static_cast<int>(std::lround(aim.y() - h / 2.0)), 0, im.height - h);
    return ImagePart{GreyView{im.row(y0) + x0, w, h, im.stride}, Eigen::Vector2d(x0, y0)};
}

// `source` made into `kind`, or what this call made of it before.
GreyView derived(const GreyView& source, SearchCache::Derived kind, SearchCache& cache, Detection& out) {
    if (const GreyView* made = cache.find(source, kind)) return *made;
    auto t = StageClock::now();
    std::vector<std::uint8_t> pixels;
    const GreyView view = kind == SearchCache::Derived::half_size     ? half_size(source, pixels)
                          : kind == SearchCache::Derived::double_size ? double_size(source, pixels)
                                                                      : smoothed(source, pixels);
    out.times.edgels_ms += ms_since(t);
    out.pixels_visited += static_cast<long>(source.width) * source.height;
    return cache.add(source, kind, std::move(pixels), view);
}

}  // namespace

Detection Detector::detect(const GreyView& im, const Eigen::Vector2d& aim, const DetectionPrior* prior) const {
    // Near a prior the frame's own size goes first (kPartOrderNearPrior), its
    // whole frame's first scan too.
    static constexpr FullSearch kPlans = full_search(), kPlansNearPrior = full_search(kPartOrderNearPrior, false);
    return detect(im, aim, prior, std::span<const SearchPlan>(prior ? kPlansNearPrior : kPlans));
}

Detection Detector::detect(const GreyView& im, const Eigen::Vector2d& aim, const DetectionPrior* prior,
                           const SearchPlan& plan) const {
    return detect(im, aim, prior, std::span<const SearchPlan>(&plan, 1));
}

Detection Detector::detect(const GreyView& im, const Eigen::Vector2d& aim, const DetectionPrior* prior,
                           std::span<const SearchPlan> plans) const {
    return detect_plans(im, aim, prior, plans, nullptr);
}

Detection Detector::detect(const GreyView& im, const Eigen::Vector2d& aim, const DetectionPrior* prior,
                           std::span<const SearchPlan> plans, SearchLimit& limit) const {
    limit.plans_done = 0;
    limit.steps_into_next = 0;
    limit.steps_run = 0;
    limit.found_plan = -1;
    limit.found_step = -1;
    limit.first_steps_into_next = 0;
    limit.first_held_steps_run = 0;
    return detect_plans(im, aim, prior, plans, &limit);
}

bool Detector::Pass::out_of_time() {
    if (stopped) return true;
    if (!limit || (plan_index == 0 && steps < limit->first_min_steps) ||
        limit->first_held_steps_run + limit->steps_run < limit->min_steps)
        return false;
    const double elapsed = std::chrono::duration<double, std::milli>(StageClock::now() - start).count();
    const double average = elapsed / std::max(1, call_steps);
    const double ms = plan_index == 0 && limit->first_ms > 0 ? limit->first_ms : limit->ms;
    if (elapsed + (limit->as_dear_as_dearest ? std::max(average, dearest_step_ms) : average) <= ms) return false;
    stopped = true;
    return true;
}

bool Detector::Pass::take_step(bool wanted) {
    if (!wanted) {
        ++steps;
        return false;
    }
    if (out_of_time()) return false;
    const int step = steps++;
    if (limit && plan_index == 0 && step >= limit->first_min_steps && step < limit->first_skip_steps) return false;
    if (limit && plan_index == 1 && step < limit->skip_steps) return false;
    if (limit && limit->as_dear_as_dearest) {
        // A step's cost: until the next one starts, with the images and
        // scans made for that one.
        const auto now = StageClock::now();
        if (call_steps > 0)
            dearest_step_ms =
                std::max(dearest_step_ms, std::chrono::duration<double, std::milli>(now - step_began).count());
        step_began = now;
    }
    ++call_steps;
    if (limit && plan_index > 0) ++limit->steps_run;
    if (limit && plan_index == 0 && step >= limit->first_min_steps) ++limit->first_held_steps_run;
    return true;
}

Detection Detector::detect_plans(const GreyView& im, const Eigen::Vector2d& aim, const DetectionPrior* prior,
                                 std::span<const SearchPlan> plans, SearchLimit* limit) const {
    Detection out;
    out.aim_image = aim;
    const auto start = StageClock::now();
    if (auto problem = describe_invalid(im); !problem.empty()) {
        out.failure = "invalid image: " + problem;
        return out;
    }
    Pass pass;
    pass.end_pair = options_.first_pass_pairs > 0 ? options_.first_pass_pairs : std::numeric_limits<int>::max();
    pass.limit = limit;
    pass.start = start;
    const char* failure = search_plans(im, aim, prior, plans, pass, out);
    for (std::size_t k = 0; k < pass.left.size(); ++k)
        if (!pass.left[k].family[0].empty()) pass.end_of_left = k + 1;
    // A search held to a time limit has no second pass: its plans are a
    // video's, which leave the later pairs out.
    if (failure && failure != kAimAtInfinity && pass.end_of_left > 0 && !limit) {
        pass.first_pair = pass.end_pair;
        pass.end_pair = std::numeric_limits<int>::max();
        pass.search = 0;
        pass.cache.start_pass();
        const char* again = search_plans(im, aim, prior, plans, pass, out);
        if (!again || again == kAimAtInfinity) failure = again;
    }
    // Another screen's field under the aim: a grid there read as a field,
    // and no grid anywhere had the windows of a candidate place of this one.
    out.another_field = failure && out.another_field_windows > 0 && out.windows < options_.provisional_votes;
    if (out.another_field) failure = kAnotherField;
    out.failure = failure ? failure : "";
    out.times.total_ms = std::chrono::duration<double, std::milli>(StageClock::now() - start).count();
    return out;
}

const char* Detector::search_plans(const GreyView& im, const Eigen::Vector2d& aim, const DetectionPrior* prior,
                                   std::span<const SearchPlan> plans, Pass& pass, Detection& out) const {
    const char* first_failure = "no grid homography";
    SearchLimit* const limit = pass.first() ? pass.limit : nullptr;
    for (std::size_t k = 0; k < plans.size(); ++k) {
        pass.plan = plans[k];
        pass.plan_index = static_cast<int>(k);
        pass.steps = 0;
        const char* failure = search_sizes(im, aim, prior, pass, out);
        if (limit && (!failure || failure == kAimAtInfinity)) {
            limit->found_plan = pass.plan_index;
            limit->found_step = pass.steps - 1;
        }
        if (!failure || failure == kAimAtInfinity) return failure;
        if (k == 0) first_failure = failure;
        if (limit && pass.stopped) {
            // Taken up here on the next frame (a stop among the steps an
            // earlier frame searched keeps their count).
            if (k == 0) limit->first_steps_into_next = std::max(pass.steps, limit->first_skip_steps);
            limit->steps_into_next = k == 0   ? limit->skip_steps
                                     : k == 1 ? std::max(pass.steps, limit->skip_steps)
                                              : pass.steps;
            break;
        }
        if (limit && k > 0) ++limit->plans_done;
        if (pass.nothing_left()) break;
    }
    return pass.first_search_failure ? pass.first_search_failure : first_failure;
}

const char* Detector::search_sizes(const GreyView& im, const Eigen::Vector2d& aim, const DetectionPrior* prior,
                                   Pass& pass, Detection& out) const {
    const SearchPlan& plan = pass.plan;
    const char* failure = search_smaller(im, aim, prior, pass, out, plan.scans, plan.smaller_scans);
    if (!failure) return nullptr;
    if (pass.first() && options_.lattice_enabled && plan.lattices != 0 &&
        (((plan.lattices & 1u) && pass.take_step() && !pass.lattice_searched && !search_lattice(im, aim, prior, out)) ||
         ((plan.lattices & ~1u) && !search_lattice_smaller(im, aim, prior, pass, out, plan.lattices >> 1))))
        return nullptr;
    const int max_side = options_.double_size_max_side;
    if (plan.double_scans != 0 && max_side > 0 && std::max(im.width, im.height) <= max_side) {
        // The part around the aim, at double size: as many pixels as the frame.
        if (const auto around = part_around(im, aim, std::clamp(options_.double_size_part, 0.1, 1.0));
            around && !search_resized(around->view, 2, around->origin, aim, prior, pass, out, plan.double_scans, 0))
            return nullptr;
    }
    if ((plan.smoothed_scans | plan.smoothed_smaller_scans) != 0 && options_.smoothed_search &&
        !pass.nothing_left() && !pass.out_of_time()) {
        const GreyView soft = derived(im, SearchCache::Derived::smoothed, pass.cache, out);
        if (!search_smaller(soft, aim, prior, pass, out, plan.smoothed_scans, plan.smoothed_smaller_scans)) {
            out.from_smoothed = true;
            return nullptr;
        }
    }
    return failure;
}

const char* Detector::search_lattice(const GreyView& im, const Eigen::Vector2d& aim, const DetectionPrior* prior,
                                     Detection& out) const {
    auto t = StageClock::now();
    const std::vector<Lattice> lattices = find_lattices(im, aim, options_.lattice);
    out.times.grid_ms += ms_since(t);
    out.pixels_visited += static_cast<long>(options_.lattice.patch_px) * options_.lattice.patch_px;
    const char* failure = "no lattice";
    for (const Lattice& l : lattices) {
        failure = read_grid(im, aim, prior, l.grid_to_image, l.rows, l.cols, out);
        if (!failure) out.from_lattice = true;
        if (!failure || failure == kAimAtInfinity) return failure;
    }
    return failure;
}

const char* Detector::search_lattice_smaller(const GreyView& im, const Eigen::Vector2d& aim,
                                             const DetectionPrior* prior, Pass& pass, Detection& out,
                                             unsigned sizes) const {
    GreyView current = im;
    double scale = 1;
    const char* failure = "no lattice";
    for (int k = 0; k < options_.lattice_sizes && (sizes >> k) != 0; ++k) {
        if (std::min(current.width, current.height) / 2 < options_.lattice.patch_px || pass.out_of_time()) break;
        current = derived(current, SearchCache::Derived::half_size, pass.cache, out);
        scale *= 0.5;
        if (!((sizes >> k) & 1u) || !pass.take_step()) continue;
        const Resizing resizing(scale, Eigen::Vector2d::Zero(), prior);
        failure = search_lattice(current, resizing.resized(aim), resizing.resized_prior(), out);
        if (failure == kAimAtInfinity) return failure;
        if (!failure) {
            resizing.carry_back(out, aim);
            return nullptr;
        }
    }
    return failure;
}

const char* Detector::search_smaller(const GreyView& im, const Eigen::Vector2d& aim, const DetectionPrior* prior,
                                     Pass& pass, Detection& out, unsigned scans, unsigned smaller_scans) const {
    const char* failure = search_scans(im, aim, prior, options_.vanishing, pass, out, scans);
    const int min_side = options_.half_size_min_side;
    if (!failure || smaller_scans == 0 || min_side <= 0 || std::min(im.width, im.height) / 2 < min_side)
        return failure;
    return search_resized(im, 0.5, Eigen::Vector2d::Zero(), aim, prior, pass, out, smaller_scans, smaller_scans)
               ? failure
               : nullptr;
}

const char* Detector::search_resized(const GreyView& part, double scale, const Eigen::Vector2d& origin,
                                     const Eigen::Vector2d& aim, const DetectionPrior* prior, Pass& pass,
                                     Detection& out, unsigned scans, unsigned smaller_scans) const {
    if (pass.nothing_left() || pass.out_of_time()) return "no grid homography";
    const GreyView resized = derived(
        part, scale < 1 ? SearchCache::Derived::half_size : SearchCache::Derived::double_size, pass.cache, out);
    const Resizing resizing(scale, origin, prior);
    const DetectionPrior* p = resizing.resized_prior();
    const Eigen::Vector2d resized_aim = resizing.resized(aim);
    // The places checked at the other sizes count against the ones checked
    // here (confirm_place's extra bits), as for any other candidate. Half
    // size goes on to smaller sizes; double size goes no further.
    const char* failure = nullptr;
    if (scale < 1) {
        failure = search_smaller(resized, resized_aim, p, pass, out, scans, smaller_scans);
    } else {
        VanishingOptions wider = options_.vanishing;
        wider.max_inlier_deg = options_.double_size_max_inlier_deg;
        failure = search_scans(resized, resized_aim, p, wider, pass, out, scans);
    }
    if (failure) return failure;
    resizing.carry_back(out, aim);
    return nullptr;
}

const char* Detector::search_scans(const GreyView& im, const Eigen::Vector2d& aim, const DetectionPrior* prior,
                                   const VanishingOptions& vanishing, Pass& pass, Detection& out,
                                   unsigned scans) const {
    // Step 1. Edgels on sparse scanlines; when nothing is found on them,
    // again on the scanlines half way between (small modules need closer
    // scanlines for their grid lines to chain), keeping what was read, down
    // to scanlines 4 pixels apart. A scan left out of `scans` is read for
    // the ones after it, not searched.
    const char* const not_searched = "no grid homography";
    if (pass.nothing_left() || scans == 0) return not_searched;
    // Each step's whole scan, made once in this call: a later part, or the
    // second pass, starts from where an earlier one left off.
    std::deque<EdgelScan>& steps = pass.cache.scans(im);
    std::size_t step = 0;
    auto searched = [&](unsigned scan_bit, const EdgelScan& scan) {
        if (!(scans & scan_bit)) return not_searched;
        unsigned sets = pass.cache.searched_sets(im, step - 1);
        const char* failure = search_edgel_sets(im, aim, prior, vanishing, scan, pass, out, sets);
        pass.cache.searched_sets(im, step - 1) = sets;
        return failure;
    };
    auto scan_step = [&](const auto& make) -> const EdgelScan& {
        if (step >= steps.size()) {
            auto t = StageClock::now();
            steps.push_back(make());
            out.pixels_visited += steps.back().pixels_visited;
            out.times.edgels_ms += ms_since(t);
        }
        return steps[step++];
    };
    EdgelOptions edgel_options = options_.edgels;
    if (pass.plan.near_aim_first && (scans & kFirstScan) && !pass.cache.near_aim_searched(im)) {
        pass.cache.near_aim_searched(im) = true;
        const char* failure = search_near_aim(im, aim, prior, vanishing, pass, out);
        if (!failure || failure == kAimAtInfinity || pass.plan.near_aim_alone) return failure;
        const int half_min = options_.whole_frame_half_min_side;
        if (pass.plan.whole_frame_halved && half_min > 0 && std::min(im.width, im.height) / 2 >= half_min) {
            // The half-size frame's own first scan, its part around the aim
            // searched already; a lattice there leaves the frame's own size's
            // to a later part.
            const SearchPlan plan = pass.plan;
            const bool lattice_searched = pass.lattice_searched;
            pass.plan.near_aim_first = false;
            pass.field_like_alone = plan.whole_frame_field_like_alone;
            failure = search_resized(im, 0.5, Eigen::Vector2d::Zero(), aim, prior, pass, out, kFirstScan, 0);
            pass.field_like_alone = false;
            pass.plan = plan;
            pass.lattice_searched = lattice_searched;
            return failure;
        }
    }
    if (pass.out_of_time()) return not_searched;
    const EdgelScan* scan = &scan_step([&] { return find_edgels(im, edgel_options); });
    if (const auto ended = lattice_if_small(im, aim, prior, scan->edgels, pass, out)) return *ended;
    // The whole frame's first scan, at this size or (whole_frame_halved) at half.
    const bool field_like_alone = pass.field_like_alone;
    pass.field_like_alone = field_like_alone || (pass.plan.near_aim_first && pass.plan.whole_frame_field_like_alone);
    const char* failure = searched(kFirstScan, *scan);
    pass.field_like_alone = field_like_alone;
    if ((scans & ~kFirstScan) == 0) return failure;
    if (failure && options_.rescan && scan->noise_sigma >= kNoisyImage && edgel_options.across < 3 &&
        !pass.nothing_left() && !pass.out_of_time()) {
        // A noisy image (low light): a faint field's edges drown in the
        // scanlines' noise; three pixels across each line hold them, and a
        // lower bar lets the weaker ones through (the chains and the window
        // vote keep the peaks the noise makes out of the grid).
        edgel_options.across = 3;
        edgel_options.noise_deviations = options_.noisy_edge_deviations;
        scan = &scan_step([&] { return find_edgels(im, edgel_options); });
        failure = searched(kNoisyScan, *scan);
    }
    int offset = edgel_options.offset >= 0 ? edgel_options.offset : scan->step / 2;  // of the scanlines so far
    for (unsigned denser = kFirstDenserScan; failure && options_.rescan && scan->step >= 8 && !pass.nothing_left() &&
                                             !pass.out_of_time() && (scans & ~(denser - 1)) != 0;
         denser <<= 1) {
        EdgelOptions between = edgel_options;
        between.step = scan->step;
        between.offset = (offset + scan->step / 2) % scan->step;
        offset = std::min(offset, between.offset);
        scan = &scan_step([&] {
            EdgelScan more = find_edgels(im, between);
            EdgelScan whole = *scan;
            whole.edgels.insert(whole.edgels.end(), more.edgels.begin(), more.edgels.end());
            whole.step /= 2;
            whole.pixels_visited = more.pixels_visited;
            return whole;
        });
        failure = searched(denser, *scan);
    }
    return failure;
}

const char* Detector::search_near_aim(const GreyView& im, const Eigen::Vector2d& aim, const DetectionPrior* prior,
                                      const VanishingOptions& vanishing, Pass& pass, Detection& out) const {
    const char* const not_searched = "no grid homography";
    const double part = options_.near_aim_part;
    if (!(part > 0 && part < 1)) return not_searched;
    const auto around = part_around(im, aim, part);
    if (!around) return not_searched;
    EdgelOptions at_frame_step = options_.edgels;
    at_frame_step.step = scanline_step(im.width, im.height, options_.edgels);
    auto t = StageClock::now();
    const EdgelScan near = find_edgels(around->view, at_frame_step);
    out.times.edgels_ms += ms_since(t);
    out.pixels_visited += near.pixels_visited;
    // The part's edgels say whether the modules are small as well as the
    // whole frame's do: a far screen goes to the lattice before the part's
    // grids, the content's, are read in vain (tuning set, 640 x 480, a
    // photo of the tiny category: 1.81 ms median instead of 2.76).
    if (const auto ended = lattice_if_small(im, aim, prior, near.edgels, pass, out)) return *ended;
    const Resizing in_part(1, around->origin, prior);
    unsigned searched_sets = 0;
    const char* failure = search_edgel_sets(around->view, in_part.resized(aim), in_part.resized_prior(), vanishing,
                                            near, pass, out, searched_sets);
    if (!failure) {
        in_part.carry_back(out, aim);
        out.from_near_aim = true;
    }
    return failure;
}

std::optional<const char*> Detector::lattice_if_small(const GreyView& im, const Eigen::Vector2d& aim,
                                                      const DetectionPrior* prior, const std::vector<Edgel>& edgels,
                                                      Pass& pass, Detection& out) const {
    if (!(pass.plan.lattice_first_if_small && pass.first() && options_.lattice_enabled &&
          pass.take_step(!pass.lattice_searched && modules_look_small(edgels))))
        return std::nullopt;
    // A far screen: its grid lines would not be found, and the content's
    // would each be read in vain first (tuning set, single frames of the
    // tiny category at 640 x 480: 6.2 ms median without this cue, 2.2 with
    // it, 2026-11-30).
    pass.lattice_searched = true;
    const char* failure = search_lattice(im, aim, prior, out);
    if (!failure || failure == kAimAtInfinity) return failure;
    return std::nullopt;
}

const char* Detector::search_edgel_sets(const GreyView& im, const Eigen::Vector2d& aim, const DetectionPrior* prior,
                                        const VanishingOptions& vanishing, const EdgelScan& scan, Pass& pass,
                                        Detection& out, unsigned& searched_sets) const {
    // A set of the plan's: its step taken, and run unless searched before.
    auto take = [&](unsigned set) {
        if (!(pass.plan.edgel_sets & set)) return false;
        if (searched_sets & set) return pass.take_step(false);
        if (!pass.take_step()) return false;
        searched_sets |= set;
        return true;
    };
    // The same scan with fewer edgels (its pixels are counted already),
    // searched when that leaves out enough of the others to matter.
    auto subset = [&](std::vector<Edgel> edgels) {
        EdgelScan fewer;
        fewer.edgels = std::move(edgels);
        fewer.step = scan.step;
        fewer.noise_sigma = scan.noise_sigma;
        return fewer;
    };
    auto worth_a_search = [&](const EdgelScan& fewer) {
        return fewer.edgels.size() >= 40 && fewer.edgels.size() <= scan.edgels.size() * 17 / 20;
    };
    // Found, or found with the aim point off the screen's plane: either ends
    // the search.
    const char* failure = "no grid homography";
    auto searched = [&](const EdgelScan& edgels) {
        failure = search(im, aim, prior, vanishing, edgels, pass, out);
        if (failure && !pass.first_search_failure) pass.first_search_failure = failure;
        return !failure || failure == kAimAtInfinity;
    };
    // The field's own edges alone first (field_edgels.hpp): where the
    // content's edges outnumber the field's, all edgels' vanishing points and
    // grid lines are often the content's, and each wrong grid read costs as
    // much as the right one (single frames with the field at 640 x 480,
    // median: tuning set 1.74 ms with all edgels first, 1.62 this way;
    // held-out set 5.2 and 2.1).
    bool field_like_searched = false;
    if (take(kFieldLikeEdgels)) {
        auto t = StageClock::now();
        const EdgelScan field_like = subset(edgels_stepping_by(scan.edgels, commonest_edge_step(scan.edgels)));
        out.times.edgels_ms += ms_since(t);
        field_like_searched = worth_a_search(field_like);
        if (field_like_searched && searched(field_like)) return failure;
    }
    // Its step counted either way, so a search held to a time counts the
    // same steps on every frame.
    if (take(kAllEdgels) && !(pass.field_like_alone && field_like_searched) && searched(scan)) return failure;
    // A faint field under strong content: the edges less those of thin
    // lines (a spreadsheet's rules).
    if (options_.thin_line_px <= 0 || !take(kOffThinLineEdgels)) return failure;
    auto t = StageClock::now();
    const EdgelScan off_lines = subset(edgels_off_thin_lines(scan.edgels, options_.thin_line_px));
    out.times.edgels_ms += ms_since(t);
    if (worth_a_search(off_lines)) searched(off_lines);
    return failure;
}

}  // namespace umf
