#include "shared/detect/pulse_search.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

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

// The 90th percentile of |a - b| over every 4th pixel of every 4th row.
double change_p90(const std::vector<std::uint8_t>& a, const std::vector<std::uint8_t>& b, int width, int height) {
    std::vector<int> change;
    change.reserve(static_cast<std::size_t>((width / 4 + 1) * (height / 4 + 1)));
    for (int y = 0; y < height; y += 4)
        for (int x = 0; x < width; x += 4) {
            const std::size_t i = static_cast<std::size_t>(y) * width + x;
            change.push_back(std::abs(static_cast<int>(a[i]) - b[i]));
        }
    const auto p90 = change.begin() + static_cast<std::ptrdiff_t>(change.size() * 9 / 10);
    std::nth_element(change.begin(), p90, change.end());
    return *p90;
}

}  // namespace

PulseSearch::PulseSearch(PulseSearchOptions options) : options_(std::move(options)) {
    options_.frames = std::max(3, options_.frames);
    options_.min_frames = std::clamp(options_.min_frames, 3, options_.frames);
}

void PulseSearch::clear() {
    kept_.clear();
    added_since_search_ = 0;
    last_found_ = false;
    width_ = height_ = 0;
}

void PulseSearch::add(const GreyView& frame) {
    if (auto problem = describe_invalid(frame); !problem.empty()) throw std::invalid_argument("pulse search: " + problem);
    if (frame.width != width_ || frame.height != height_) {
        clear();
        width_ = frame.width;
        height_ = frame.height;
    }
    std::vector<std::uint8_t> copy;
    if (static_cast<int>(kept_.size()) >= options_.frames) {
        copy = std::move(kept_.front());  // its buffer reused
        kept_.pop_front();
    }
    copy.resize(static_cast<std::size_t>(width_) * height_);
    for (int y = 0; y < height_; ++y) std::copy_n(frame.row(y), width_, copy.data() + static_cast<std::size_t>(y) * width_);
    kept_.push_back(std::move(copy));
    ++added_since_search_;
}

bool PulseSearch::due() const {
    return frames() >= options_.min_frames && (last_found_ || added_since_search_ >= options_.search_every ||
                                               added_since_search_ == frames());
}

bool PulseSearch::at_rest() const {
    const auto& last = kept_.back();
    const double near = change_p90(last, kept_[kept_.size() - 2], width_, height_);
    const double far = change_p90(last, kept_.front(), width_, height_);
    return far <= options_.rest_factor * near + options_.rest_levels;
}

// The shape at the rate and phase that follow the course best, scaled to
// [-1, 1] with its sign; empty when none follows it well enough.
std::vector<double> PulseSearch::fit_shape(const std::vector<double>& course) const {
    const PulseShape& shape = *options_.shape;
    if (!shape.waveform || !(shape.period_s > 0)) return {};
    constexpr int kPhases = 64;
    std::vector<double> best, trial(course.size());
    double best_fit = options_.min_fit;
    for (const double rate : options_.frame_rates) {
        if (!(rate > 0)) continue;
        for (int p = 0; p < kPhases; ++p) {
            for (std::size_t i = 0; i < course.size(); ++i) {
                const double phase = static_cast<double>(i) / (shape.period_s * rate) + static_cast<double>(p) / kPhases;
                trial[i] = shape.waveform(phase - std::floor(phase));
            }
            const double fit = correlation(course, trial);
            if (std::abs(fit) <= best_fit) continue;
            best_fit = std::abs(fit);
            best = trial;
            const auto [lo, hi] = std::minmax_element(best.begin(), best.end());
            const double mid = (*hi + *lo) / 2, half = (*hi - *lo) / 2;
            for (double& v : best) v = half > 0 ? (fit > 0 ? 1 : -1) * (v - mid) / half : 0;
        }
    }
    return best;
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
    if (!at_rest()) {
        out.detection.failure = "the view moved";
        return out;
    }
    std::vector<GreyView> views;
    for (const auto& f : kept_) views.push_back({f.data(), width_, height_, width_});
    const PulseCourse course = find_pulse_course(views);
    out.share = course.share;
    if (course.level.empty() || course.share < options_.min_share) {
        out.detection.failure = "no pulse in the frames";
        return out;
    }
    std::vector<double> level = course.level;
    if (options_.shape) {
        if (auto fitted = fit_shape(course.level); !fitted.empty()) {
            level = std::move(fitted);
            out.fitted = true;
        }
    }
    PulseDemodulator demodulator;
    for (std::size_t i = 0; i < views.size(); ++i) demodulator.add(views[i], std::clamp(0.5 + 0.5 * level[i], 0.0, 1.0));
    const GreyView field = demodulator.field_image(PulseDemodulator::SlopeScale::spread);
    if (!field.data) {
        out.detection.failure = "no pulse in the frames";
        return out;
    }
    // The course's sign is not known: the field shows in the image or in
    // its inverse, which the course of the other sign would give.
    const std::span<const SearchPlan> plans(options_.plans);
    out.detection = detector.detect(field, aim, nullptr, plans);
    if (!out.detection.found) {
        std::vector<std::uint8_t> inverse(field.data, field.data + static_cast<std::size_t>(field.width) * field.height);
        for (auto& v : inverse) v = static_cast<std::uint8_t>(255 - v);
        Detection d = detector.detect(GreyView{inverse.data(), field.width, field.height, field.width}, aim, nullptr, plans);
        if (d.found) out.detection = std::move(d);
    }
    last_found_ = out.detection.found;
    return out;
}

}  // namespace umf
