#include "shared/detect/pulse_search.hpp"

#include <Eigen/Dense>
#include <algorithm>
#include <array>
#include <cmath>

#include "shared/detect/field_shift.hpp"
#include "shared/detect/homography.hpp"
#include "shared/detect/pulse_course.hpp"
#include "shared/detect/pulse_demodulator.hpp"

namespace umf {

namespace {

double correlation(const std::vector<double>& a, const std::vector<double>& b) {
    const double n = static_cast<double>(a.size());
    double ma = 0, mb = 0;
    for (std::size_t i = 0; i < a.size(); ++i) ma += a[i] / n, mb += b[i] / n;
    double ab = 0, aa = 0, bb = 0;
    for (std::size_t i = 0; i < a.size(); ++i) {
        ab += (a[i] - ma) * (b[i] - mb);
        aa += (a[i] - ma) * (a[i] - ma);
        bb += (b[i] - mb) * (b[i] - mb);
    }
    return aa > 0 && bb > 0 ? ab / std::sqrt(aa * bb) : 0;
}

// How alike a course is to itself a frame later, from -1 to 1: near 1 for a
// slow course, near 0 or below for one that jumps from frame to frame.
double lag_one_correlation(const std::vector<double>& course) {
    const double n = static_cast<double>(course.size());
    double mean = 0;
    for (const double v : course) mean += v / n;
    double along = 0, all = 0;
    for (std::size_t i = 0; i < course.size(); ++i) {
        all += (course[i] - mean) * (course[i] - mean);
        if (i + 1 < course.size()) along += (course[i] - mean) * (course[i + 1] - mean);
    }
    return all > 0 ? along / all : 0;
}

// The median ratio of `frame`'s grey levels to `reference`'s over the pixels
// (every `step`-th along rows and columns) that `to_reference` takes from
// inside `frame` and that are not too dark to tell a ratio: 1 where too few.
double exposure_ratio(const GreyView& frame, const GreyView& reference, const Eigen::Matrix3d& to_reference,
                      int step = 4) {
    constexpr int kDarkest = 24;
    const Eigen::Matrix3d back = to_reference.inverse();
    std::vector<float> ratios;
    for (int y = 0; y < reference.height; y += step)
        for (int x = 0; x < reference.width; x += step) {
            const int r = reference.at(x, y);
            if (r < kDarkest) continue;
            const Eigen::Vector3d q = back * Eigen::Vector3d(x, y, 1);
            if (q.z() <= 0) continue;
            const double sx = q.x() / q.z(), sy = q.y() / q.z();
            if (!(sx >= 0 && sy >= 0 && sx < frame.width - 1 && sy < frame.height - 1)) continue;
            ratios.push_back(static_cast<float>(frame.at(x, y)) / static_cast<float>(r));
        }
    if (ratios.size() < 64) return 1;
    const auto mid = ratios.begin() + static_cast<std::ptrdiff_t>(ratios.size() / 2);
    std::nth_element(ratios.begin(), mid, ratios.end());
    return *mid > 0 ? *mid : 1;
}

// `view`'s grey levels divided by `gain`, into `buffer` (which may be the
// view's own pixels), through a table of the 256 levels.
GreyView scaled(const GreyView& view, double gain, std::vector<std::uint8_t>& buffer) {
    std::uint8_t table[256];
    for (int v = 0; v < 256; ++v) table[v] = static_cast<std::uint8_t>(std::min(255.0, v / gain + 0.5));
    buffer.resize(static_cast<std::size_t>(view.width) * static_cast<std::size_t>(view.height));
    for (int y = 0; y < view.height; ++y) {
        const std::uint8_t* src = view.row(y);
        std::uint8_t* dst = buffer.data() + static_cast<std::size_t>(y) * view.width;
        for (int x = 0; x < view.width; ++x) dst[x] = table[src[x]];
    }
    return {buffer.data(), view.width, view.height, view.width};
}

// A detection on a pyramid level's image, in the frame's own pixels.
Detection in_frame_pixels(Detection d, const LevelMap& level) {
    d.image_to_field = d.image_to_field * level.from_frame();
    d.aim_image = level.to_frame(d.aim_image);
    d.size_scale /= level.scale();
    return d;
}

// `view`'s grey levels inverted (255 - v), into `buffer`: the demodulated
// image of the course's other sign.
GreyView inverted(const GreyView& view, std::vector<std::uint8_t>& buffer) {
    buffer.resize(static_cast<std::size_t>(view.width) * static_cast<std::size_t>(view.height));
    for (int y = 0; y < view.height; ++y) {
        const std::uint8_t* src = view.row(y);
        std::uint8_t* dst = buffer.data() + static_cast<std::size_t>(y) * view.width;
        for (int x = 0; x < view.width; ++x) dst[x] = static_cast<std::uint8_t>(255 - src[x]);
    }
    return {buffer.data(), view.width, view.height, view.width};
}

}  // namespace

PulseSearch::PulseSearch(PulseSearchOptions options) : options_(std::move(options)) {
    options_.frames = std::max(3, options_.frames);
    options_.min_frames = std::clamp(options_.min_frames, 3, options_.frames);
}

void PulseSearch::clear() {
    kept_.clear();
    stray_.reset();
    motion_.reset();
    earlier_motion_.reset();
    found_.reset();
    added_since_search_ = 0;
    last_found_ = false;
    width_ = height_ = 0;
}

bool PulseSearch::due() const {
    return frames() >= options_.min_frames && (last_found_ || added_since_search_ >= options_.search_every ||
                                               added_since_search_ == frames());
}

// The shape at the rate and phase whose course explains most of the
// frames' variation over time (t' C t, t the course less its mean and of
// unit length, C the frames' covariance), scaled to [-1, 1]; empty where the
// shape has none, or where the frames' leading course is smooth and the
// shape does not follow it. Not the shape nearest the leading course: at a
// pulse of a few percent over moving content, that course is the content's
// frame-to-frame leakage through the registrations (the tuning document's
// at 12 frames jumped between +1 and -0.66 from one frame to the next, and
// no phase of the sine followed it), while the pulse is the strongest course
// of the announced shape. Chosen so, the tuning set's first right frame came
// at 20 frames kept, not 44-57 (umf_pulse_benchmark).
std::vector<double> PulseSearch::fit_shape(const PulseCourse& found) const {
    const PulseShape& shape = *options_.shape;
    const auto n = static_cast<Eigen::Index>(found.level.size());
    if (!shape.waveform || !(shape.period_s > 0) || found.covariance.rows() != n) return {};
    constexpr int kPhases = 64;
    std::vector<double> best;
    Eigen::VectorXd trial(n);
    double most = 0;
    // Each frame's time from the first kept (seconds): its own where every
    // frame kept has one (a page drops frames while it is busy), else the
    // frame's number at each rate tried.
    const bool timed = static_cast<Eigen::Index>(kept_.size()) == n &&
                       std::all_of(kept_.begin(), kept_.end(), [](const Kept& k) { return k.time_s.has_value(); });
    const std::vector<double> rates = timed ? std::vector<double>{1.0} : options_.frame_rates;
    for (const double rate : rates) {
        if (!(rate > 0)) continue;
        for (int p = 0; p < kPhases; ++p) {
            for (Eigen::Index i = 0; i < n; ++i) {
                const Kept& k = kept_[static_cast<std::size_t>(i)];
                const double t = timed ? *k.time_s - *kept_.front().time_s
                                       : static_cast<double>(k.number - kept_.front().number) / rate;
                const double phase = t / shape.period_s + static_cast<double>(p) / kPhases;
                trial(i) = shape.waveform(phase - std::floor(phase));
            }
            trial.array() -= trial.mean();
            const double norm = trial.norm();
            if (!(norm > 0)) continue;
            const double explained = trial.dot(found.covariance * trial) / (norm * norm);
            if (explained <= most) continue;
            most = explained;
            best.assign(trial.data(), trial.data() + n);
        }
    }
    if (best.empty()) return best;
    // A leading course as smooth as a pulse that the shape does not follow
    // is a pulse of another shape (the announced one wrong): the course is
    // used. A course of leakage jumps from frame to frame: on the tuning
    // set's searches that found the field through the shape, every leading
    // course smoother than kSmooth followed the shape at a correlation of
    // 0.79 or more (umf_pulse_benchmark --frames 80).
    constexpr double kSmooth = 0.7, kFollows = 0.5;
    const double follows = correlation(found.level, best);
    if (lag_one_correlation(found.level) > kSmooth && std::abs(follows) < kFollows) return {};
    const auto [lo, hi] = std::minmax_element(best.begin(), best.end());
    const double mid = (*hi + *lo) / 2, half = (*hi - *lo) / 2;
    const double sign = follows < 0 ? -1 : 1;
    for (double& v : best) v = sign * (v - mid) / half;
    return best;
}

// The field alone at either sign, where the pulse's range is announced and
// the course is its shape: the slope image is the field less the content
// (F - C), so content as strong as the field (a spreadsheet's digits, a web
// page's text) is there at the field's contrast, while each frame's line
// followed out to opacity 1 is the field alone (full_opacity_image). Views
// of alone_pixels_, valid until the next search; empty where not announced.
std::vector<GreyView> PulseSearch::field_alone_images(PulseDemodulator& demodulator, bool fitted) {
    std::vector<GreyView> out;
    const PulseShape* shape = options_.shape ? &*options_.shape : nullptr;
    if (!options_.field_alone || !fitted || !shape || !(shape->opacity_max > shape->opacity_min)) return out;
    std::size_t i = 0;
    for (const auto& [zero, one] :
         {std::pair{shape->opacity_min, shape->opacity_max}, std::pair{shape->opacity_max, shape->opacity_min}}) {
        const GreyView alone = demodulator.full_opacity_image(zero, one);
        if (!alone.data) continue;
        alone_pixels_[i].assign(alone.data, alone.data + static_cast<std::size_t>(alone.width) * alone.height);
        out.push_back({alone_pixels_[i++].data(), alone.width, alone.height, alone.width});
    }
    return out;
}

// The slope with the content's leakage taken out, and its inverse: views
// of content_free_pixels_, valid until the next search; empty views where
// the demodulator has no slope.
std::array<GreyView, 2> PulseSearch::content_free_images(PulseDemodulator& demodulator) {
    const int width = demodulator.width();
    const int tile = std::max(8, static_cast<int>(std::lround(options_.content_free_tile * width)));
    const GreyView free = demodulator.content_free_field_image(tile);
    if (!free.data) return {};
    content_free_pixels_[0].assign(free.data, free.data + static_cast<std::size_t>(free.width) * free.height);
    const GreyView kept{content_free_pixels_[0].data(), free.width, free.height, free.width};
    return {kept, inverted(kept, content_free_pixels_[1])};
}

bool PulseSearch::demodulate(int level, PulseDemodulator& demodulator, PulseSearchResult& out) {
    // Every frame laid onto the newest: the content stays where it is in
    // the newest, and the field is found there.
    const LevelMap at_level(level);
    const GreyView newest = kept_.back().pyramid.level(level);
    warped_.resize(kept_.size());
    std::vector<GreyView> views;
    std::vector<Eigen::Matrix3d> to_newest;
    for (const Kept& k : kept_) to_newest.push_back(at_level.homography(k.to_newest));
    for (std::size_t i = 0; i < kept_.size(); ++i)
        views.push_back(i + 1 == kept_.size()
                            ? newest
                            : warp_frame(kept_[i].pyramid.level(level), to_newest[i], newest, warped_[i]));
    if (options_.level_exposure)
        for (std::size_t i = 0; i + 1 < views.size(); ++i) {
            const double gain = exposure_ratio(views[i], newest, to_newest[i]);
            if (std::abs(gain - 1) > 1e-3) views[i] = scaled(views[i], gain, warped_[i]);
        }
    const PulseCourse course = find_pulse_course(views);
    out.share = course.share;
    if (course.level.empty() || course.share < options_.min_share) {
        out.detection.failure = "no pulse in the frames";
        return false;
    }
    std::vector<double> opacity = course.level;
    out.fitted = false;
    if (options_.shape) {
        if (auto fitted = fit_shape(course); !fitted.empty()) {
            opacity = std::move(fitted);
            out.fitted = true;
        }
    }
    for (std::size_t i = 0; i < views.size(); ++i)
        demodulator.add(views[i], std::clamp(0.5 + 0.5 * opacity[i], 0.0, 1.0));
    out.course = std::move(opacity);
    return true;
}

// The course's sign is not known: the field shows in the image or in its
// inverse, which the course of the other sign would give. A place carried
// here is confirmed where it is said to be first: far cheaper than a
// search, and it reads a field too faint for one. Found again, it is
// carried on from here, the registrations' drift gone. Each pair of images
// is followed and then searched before the next is made (the field alone
// followed before the slope was searched placed one frame of the tuning
// set's blank page wrong); where none holds the field, the slope's search
// says why. `follow_only`: no search, the content-free slope not made.
bool PulseSearch::look(const Detector& detector, const Eigen::Vector2d& aim, int level, PulseDemodulator& demodulator,
                       PulseSearchResult& out, bool follow_only) {
    const GreyView field = demodulator.field_image(PulseDemodulator::SlopeScale::spread);
    if (!field.data) {
        out.detection.failure = "no pulse in the frames";
        return false;
    }
    std::vector<std::uint8_t> inverse_pixels;
    const GreyView inverse = inverted(field, inverse_pixels);
    bool followed = false;
    const LevelMap at_level(level);
    const Eigen::Vector2d level_aim = at_level.from_frame(aim);
    auto look_in = [&](std::span<const GreyView> images, std::span<const SearchPlan> plans, bool follow = true) {
        if (follow && found_ && options_.follow_carried)
            for (const GreyView& image : images) {
                out.detection = in_frame_pixels(
                    detector.follow(image, level_aim, found_->image_to_field * at_level.to_frame()), at_level);
                if ((followed = out.detection.found)) return;
            }
        if (follow_only) return;
        for (std::size_t i = 0; i < images.size(); ++i) {
            Detection d = in_frame_pixels(detector.detect(images[i], level_aim, nullptr, plans), at_level);
            if (d.found || i == 0) out.detection = std::move(d);
            if (out.detection.found) return;
        }
    };
    look_in(std::array{field, inverse}, options_.plans);
    if (!out.detection.found) {
        const Detection slope_failure = out.detection;
        const std::vector<GreyView> alone = field_alone_images(demodulator, out.fitted);
        if (!alone.empty()) look_in(alone, options_.plans);
        if (!out.detection.found && !follow_only && options_.content_free_tile > 0) {
            const std::array<GreyView, 2> content_free = content_free_images(demodulator);
            // Searched, not followed: a carried place confirmed there, frame
            // after frame, crept off on the tuning set's noisy web page (26
            // frames wrong, up to 2 modules; umf_pulse_benchmark --noise 6
            // --jpeg-quality 40).
            if (content_free[0].data) look_in(content_free, options_.content_free_plans, false);
        }
        if (!out.detection.found) out.detection = slope_failure;
    }
    return followed;
}

PulseSearchResult PulseSearch::search(const Detector& detector, const Eigen::Vector2d& aim) {
    PulseSearchResult out;
    added_since_search_ = 0;
    last_found_ = false;
    out.frames = frames();
    out.detection.aim_image = aim;
    if (out.frames < options_.min_frames) {
        out.detection.failure = "too few frames for the pulse";
        return out;
    }
    // A place carried is followed at the smaller level first; where it is
    // not confirmed there, everything runs at the frames' own size.
    bool followed = false;
    if (const int level = std::min(options_.demodulation_level, kept_.back().pyramid.levels() - 1);
        level > 0 && found_ && options_.follow_carried) {
        PulseDemodulator demodulator;
        if (demodulate(level, demodulator, out)) followed = look(detector, aim, level, demodulator, out, true);
    }
    if (!followed) {
        out.detection = Detection{};
        out.detection.aim_image = aim;
        PulseDemodulator demodulator;
        if (!demodulate(0, demodulator, out)) return out;
        followed = look(detector, aim, 0, demodulator, out, false);
    }
    if (out.detection.found && !holds_in_newest(out.detection, detector.field())) {
        out.detection.found = false;
        out.detection.failure = "the newest frame's field lies elsewhere";
        followed = false;
    }
    last_found_ = out.detection.found;
    if (followed) {
        // The follow's place at the aim is kept; where its map's shape
        // around the aim departs from the carried map's, the carried map's
        // shape is carried on from that place.
        Detection kept = out.detection;
        if (shape_distance(found_->image_to_field, image_to_field_through_aim(kept), aim, kShapeReach * width_) >
            options_.max_follow_shape_change)
            kept.image_to_field = found_->image_to_field;
        keep_found(kept);
    } else if (out.detection.found) {
        keep_found(out.detection);
    }
    return out;
}

bool PulseSearch::holds_in_newest(const Detection& place, const Field& field) const {
    if (!options_.check_newest || kept_.empty()) return true;
    const FramePyramid& newest = stray_ ? stray_->pyramid : kept_.back().pyramid;
    const FieldShift f = field_shift(newest.level(0), field, place.image_to_field);
    const bool elsewhere = f.measured && f.best_t >= options_.elsewhere_t &&
                           f.best_t >= options_.elsewhere_over_content * f.content_t &&
                           f.place_t < options_.place_share * f.best_t &&
                           f.shift.norm() >= options_.elsewhere_modules * f.module_px;
    return !elsewhere;
}

void PulseSearch::found_elsewhere(const Detection& found) {
    if (!found.found || kept_.empty()) return;
    // Found in a frame set aside: the frames kept start over from it.
    if (stray_) start_over_from_stray();
    keep_found(found);
}

// Carried by its map through the aim: the map is fitted to the whole view,
// the aim's place read from the module edges around it, and the two can
// differ by a fifth of a module on a tracker's lock (the tuning set's
// document: 0.07 module off at the tracker's last lock, 0.30 on the first
// frame carried from its map), an error every carried frame would start from.
void PulseSearch::keep_found(const Detection& found) {
    found_ = found;
    found_->image_to_field = image_to_field_through_aim(found);
    carried_for_ = 0;
    through_detail_ = false;
}

// The aim the place was found at, where the carried map now puts it on the
// field against where it was then: the page's aim stays at the frame's centre.
bool PulseSearch::near_found() const {
    const std::optional<Carry> c = carry(found_->aim_image);
    return options_.detail_carry_modules > 0 && c && c->travel <= options_.detail_carry_modules;
}

std::optional<PulseSearch::Carry> PulseSearch::carry(const Eigen::Vector2d& aim) const {
    if (!found_ || stray_) return std::nullopt;
    const std::optional<Point2> at = apply_homography(found_->image_to_field, aim);
    if (!at) return std::nullopt;
    return Carry{carried_for_, (*at - found_->aim_field).norm()};
}

std::optional<Detection> PulseSearch::carried(const Eigen::Vector2d& aim) const {
    if (!found_ || stray_) return std::nullopt;
    const std::optional<Point2> at = apply_homography(found_->image_to_field, aim);
    if (!at) return std::nullopt;
    Detection d = *found_;
    d.aim_image = aim;
    d.aim_field = *at;
    d.from_prior = true;
    d.times = {};
    return d;
}

}  // namespace umf
