// A field too faint for any one frame, found in the last frames together:
// they are demodulated (pulse_demodulator.hpp) against the pulse's course,
// found from the frames (pulse_course.hpp) and, where the pulse's shape is
// known (the welcome's period and waveform), fitted to that shape, and the
// detector reads the demodulated image. The frames must show the screen in
// the same place: a camera at rest (a kiosk's, a phone laid down or held on
// a stand); the frames of a view that moves are not searched (a cheap
// look at how much the frames changed, PulseSearchOptions::rest_factor). A
// hand-held phone's frames would first have to be registered onto each
// other, which this does not do yet.
#pragma once

#include <Eigen/Core>
#include <cstdint>
#include <deque>
#include <functional>
#include <optional>
#include <vector>

#include "shared/detect/detector.hpp"
#include "shared/detect/image.hpp"
#include "shared/detect/search_plan.hpp"

namespace umf {

struct PulseShape {
    // The opacity over one period (phase 0..1, opacity in any scale).
    std::function<double(double phase)> waveform;
    double period_s = 0;
};

struct PulseSearchOptions {
    int frames = 24;      // kept, the oldest dropped first
    int min_frames = 8;   // before the first search
    // Of the frames' variation over time, the share the pulse's course must
    // explain before the detector is asked (noise alone: about 1 / frames).
    double min_share = 0.2;
    std::optional<PulseShape> shape;
    // The frame rates tried when fitting the shape: image files carry none.
    std::vector<double> frame_rates = {24, 25, 30, 50, 60};
    // A fit below this correlation with the course is not taken; the
    // course itself is used.
    double min_fit = 0.8;
    // The view at rest: the 90th percentile of the grey level's change from
    // the first frame kept to the last at most `rest_factor` times that
    // from the last but one to the last, plus `rest_levels` (a pulse of a
    // few percent changes a pixel by a few levels; a view that moves, by
    // tens at every edge, more the longer it moves).
    double rest_factor = 2;
    double rest_levels = 6;
    // A search that found nothing is not tried again until this many more
    // frames are kept (one that found the field is tried on every frame).
    int search_every = 4;
    // What the detector runs on a demodulated image: the first scan of a
    // video's frame, then the scan three pixels across and the image
    // smoothed (search_plan.hpp's parts 2 and 5): the demodulated image's
    // noise is a frame's over the pulse's small spread, tens of grey levels
    // from pixel to pixel, more from fewer frames. Its field is sharp and at
    // the content's contrast, or not there at all; the other fallbacks would
    // cost an image without it some 50 ms each time.
    std::vector<SearchPlan> plans = {spread_first(), search_part(2), search_part(5)};
};

struct PulseSearchResult {
    Detection detection;  // holds for every frame kept (they are at rest)
    int frames = 0;       // kept when searching
    double share = 0;     // of their variation explained by the course
    bool fitted = false;  // the course fitted to PulseSearchOptions::shape
};

class PulseSearch {
public:
    explicit PulseSearch(PulseSearchOptions options = {});

    // Copies the frame; one of another size than those kept starts over.
    void add(const GreyView& frame);
    void clear();
    int frames() const { return static_cast<int>(kept_.size()); }

    // Whether a search is worth its cost now: enough frames kept, and
    // search_every more since a search that found nothing.
    bool due() const;
    // The field in the frames kept, or a detection that says why not.
    PulseSearchResult search(const Detector& detector, const Eigen::Vector2d& aim);

private:
    std::vector<double> fit_shape(const std::vector<double>& course) const;
    bool at_rest() const;

    PulseSearchOptions options_;
    int width_ = 0, height_ = 0;
    int added_since_search_ = 0;
    bool last_found_ = false;
    std::deque<std::vector<std::uint8_t>> kept_;
};

}  // namespace umf
