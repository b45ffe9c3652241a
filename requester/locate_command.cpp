#include "requester/locate_command.hpp"

#include <unistd.h>

#include <cerrno>
#include <cmath>
#include <cstring>
#include <memory>
#include <nlohmann/json.hpp>
#include <stdexcept>

#include "requester/frame_source.hpp"
#include "requester/grey_frame.hpp"
#include "requester/json_lines.hpp"
#include "shared/detect/detector.hpp"
#include "shared/detect/image.hpp"
#include "shared/detect/pulse_tracker.hpp"
#include "shared/field/field_io.hpp"
#include "shared/overlay/pulse_shape.hpp"

namespace umf::requester {

const char* const kLocateUsage = R"(umf-requester locate: which field point a camera image is aimed at

usage:
  umf-requester locate --field F.json [--sequence] [--aim X,Y] IMAGE...
  umf-requester locate --field F.json [--sequence] [--aim X,Y] --video FILE
  umf-requester locate --field F.json --sequence [--pulse-period S --waveform sine|triangle
                                            [--pulse-opacities MIN,MAX]] IMAGE...

Finds the field of F.json in each IMAGE (any format OpenCV decodes) or in every
frame of the video FILE, and prints one JSON object per line and frame, each line
flushed as soon as its frame is done:
  {"frame": i, "found": true, "point": [u, v], "H": [9 numbers], "windows": n,
   "ms": t, "confidence": c}
  {"frame": i, "found": false, "ms": t, "reason": "why the detector gave up"}
  {"frame": i, "found": false, "error": "cannot decode IMAGE: why"}

  frame       counts the frames read, from 0; an unreadable image takes its number too
  point       the field point (u, v), in modules, under the aim point
  H           image pixels -> field modules, 3 x 3 row-major, scaled to H[8] = 1
              where possible
  windows     how many field windows agreed on the place
  ms          the detection time in milliseconds (decoding not included)
  confidence  the fraction of the modules read that the place explains
  reason      the stage that gave up; "another field": a marker field is under the
              aim point, but not F.json's (another screen's)

options:
  --field F.json  the field shown on the screen (umf-field/1)
  --aim X,Y       the aim point in image pixels, continuous coordinates: the centre
                  of pixel (0, 0) is 0.5,0.5; default the image centre
  --video FILE    read the frames of a video (anything cv::VideoCapture opens)
                  instead of image files
  --sequence      the frames are consecutive frames of one camera: track the field
                  from frame to frame, which holds it at lower opacity and through
                  blur. Adds "state": "locked" | "lost" | "searching", "prior"
                  (the lock came from the previous place) and "raw_point" (this
                  frame's own point); "point" is then the smoothed aim point and
                  "found" is true exactly when locked. Without --sequence every
                  frame, a video's too, is detected on its own.
                  A field too faint for any one frame is looked for in the last 24
                  frames together while nothing is locked: its pulse is found in
                  them and the field demodulated out of the content, the frames
                  first laid onto the newest (a hand-held camera's move; a cut
                  starts the frames over). Such a line is
                  "state": "locked" with "demodulated": true and "pulse_frames": n
                  after the keys above. With --sequence "ms" is the frame's whole
                  work: the tracker, laying the frame onto the last, and the
                  search of the frames together where it ran. Once found (by
                  that search, or locked on a frame alone), the field is
                  carried from frame to frame as the frames move ("prior":
                  true) until it is found again, for at most 60 frames.
  --pulse-period S  with --sequence: the period of the field's pulse in seconds, as
                  the provider's welcome gives it; the pulse is taken to be that
                  shape at the rate (24, 25, 30, 50 or 60 frames a second, or the
                  video's) and phase that explain the frames' change the most.
                  Without it the pulse is taken as the frames show it.
  --waveform W    with --pulse-period: sine (the default) or triangle
  --pulse-opacities MIN,MAX
                  with --pulse-period: the opacities the pulse runs between, as the
                  welcome's overlay gives them (opacity_min, opacity_max); the
                  content is then taken out of the frames searched together, the
                  field alone looked for where the content hides it.

exit codes: 0 the frames were read (frames without the field and unreadable images
            are reported in their lines); 2 wrong usage; 3 the field file or the
            video could not be read, or the output could not be written.
)";

namespace {

// Three decimals: microseconds are noise in a timing.
double round_ms(double ms) { return std::round(ms * 1000) / 1000; }

Json point_json(const Eigen::Vector2d& p) { return Json::array({p.x(), p.y()}); }

// Row-major, divided by H[8] when that is not (nearly) zero; otherwise scaled
// to unit norm so the numbers stay readable.
Json homography_json(const Eigen::Matrix3d& h) {
    const double norm = h.norm();
    double scale = std::abs(h(2, 2)) > 1e-12 * norm ? h(2, 2) : norm;
    if (!(scale != 0 && std::isfinite(scale))) scale = 1;
    Json out = Json::array();
    for (int r = 0; r < 3; ++r)
        for (int c = 0; c < 3; ++c) out.push_back(h(r, c) / scale);
    return out;
}

Json detection_json(int frame, const Detection& d, const Eigen::Vector2d& point) {
    Json j;
    j["frame"] = frame;
    j["found"] = d.found;
    if (d.found) {
        j["point"] = point_json(point);
        j["H"] = homography_json(image_to_field_through_aim(d));
        j["windows"] = d.windows;
        j["ms"] = round_ms(d.times.total_ms);
        j["confidence"] = d.confidence;
    } else {
        j["ms"] = round_ms(d.times.total_ms);
        j["reason"] = d.failure;
    }
    return j;
}

Json tracked_json(int frame, const TrackResult& t) {
    const bool locked = t.state == TrackState::locked;
    Json j = detection_json(frame, t.detection, locked ? t.aim_field : t.detection.aim_field);
    j["found"] = locked;  // a detection the tracker did not lock on is no place
    j["state"] = to_string(t.state);
    j["prior"] = t.used_prior;
    if (locked) j["raw_point"] = point_json(t.detection.aim_field);
    return j;
}

// A frame of a sequence: the tracker's lock, or the place the pulse search
// found in the frames kept with it or carried there from the last frame
// where it did; "ms" is the whole update.
Json sequence_json(int frame, const PulseTrackResult& r) {
    Json j = tracked_json(frame, r.track);
    j["ms"] = round_ms(r.ms);
    if (r.demodulated) {
        j["demodulated"] = true;
        j["pulse_frames"] = r.pulse_frames;
    }
    return j;
}

PulseSearchOptions pulse_search_options(const LocateOptions& o, double video_fps) {
    PulseSearchOptions options;
    if (!o.pulse_period_s) return options;
    const auto [lo, hi] = o.pulse_opacities.value_or(std::pair{0.0, 0.0});
    options.shape = overlay::announced_pulse_shape(o.waveform, *o.pulse_period_s, lo, hi);
    if (video_fps > 0) options.frame_rates = {video_fps};
    return options;
}

}  // namespace

LocateOptions parse_locate_args(int argc, char** argv, int first) {
    const Args a = parse_args(argc, argv, first, {"field", "aim", "video", "pulse-period", "waveform", "pulse-opacities"},
                              {"sequence"});
    LocateOptions o;
    auto field = get(a, "field");
    if (!field) throw UsageError("locate needs --field F.json");
    o.field_path = *field;
    o.sequence = has_flag(a, "sequence");
    if (auto aim = get(a, "aim")) {
        auto [x, y] = parse_point("aim", *aim);
        o.aim = Eigen::Vector2d(x, y);
    }
    if (auto period = get(a, "pulse-period")) {
        if (!o.sequence) throw UsageError("--pulse-period needs --sequence: a pulse is seen over frames");
        o.pulse_period_s = parse_pulse_period(*period);
    }
    if (auto waveform = get(a, "waveform")) {
        if (!o.pulse_period_s) throw UsageError("--waveform goes with --pulse-period");
        const auto w = overlay::waveform_from_string(*waveform);
        if (!w) throw UsageError("--waveform must be sine or triangle, not '" + *waveform + "'");
        o.waveform = *w;
    }
    if (auto range = get(a, "pulse-opacities")) {
        if (!o.pulse_period_s) throw UsageError("--pulse-opacities goes with --pulse-period");
        const auto [lo, hi] = parse_point("pulse-opacities", *range);
        if (!(lo >= 0 && lo < hi && hi <= 1))
            throw UsageError("--pulse-opacities must be MIN,MAX with 0 <= MIN < MAX <= 1, not '" + *range + "'");
        o.pulse_opacities = std::pair{lo, hi};
    }
    o.video = get(a, "video");
    o.images = a.positional;
    if (o.video && !o.images.empty()) throw UsageError("locate reads either image files or --video FILE, not both");
    if (!o.video && o.images.empty()) throw UsageError("locate needs image files or --video FILE");
    return o;
}

int run_locate(const LocateOptions& o, std::FILE* out) {
    const Field field = load_field(o.field_path);
    std::unique_ptr<Detector> detector;
    try {
        detector = std::make_unique<Detector>(field);
    } catch (const std::invalid_argument& e) {
        throw FieldFileError(o.field_path + ": " + e.what());
    }
    std::unique_ptr<FrameSource> source = o.video ? video_file(*o.video) : image_files(o.images);
    std::optional<PulseTracker> tracker;
    if (o.sequence) tracker.emplace(*detector, TrackerOptions{}, pulse_search_options(o, source->fps()));

    std::vector<std::uint8_t> luma;  // reused between frames
    int frames = 0, found = 0, unreadable = 0;
    while (auto frame = source->next()) {
        ++frames;
        std::string why = frame->error;
        GreyView view;
        if (why.empty()) {
            view = grey_view(frame->pixels, luma, why);
            if (!why.empty()) why = "cannot decode " + frame->name + ": " + why;
        }
        if (!why.empty()) {
            ++unreadable;
            Json j;
            j["frame"] = frame->index;
            j["found"] = false;
            j["error"] = why;
            write_line(out, j);
            continue;
        }
        const Eigen::Vector2d aim = o.aim.value_or(Eigen::Vector2d(view.width / 2.0, view.height / 2.0));
        Json j;
        if (tracker) {
            j = sequence_json(frame->index, tracker->update(view, aim));
        } else {
            const Detection d = detector->detect(view, aim);
            j = detection_json(frame->index, d, d.aim_field);
        }
        found += j["found"].get<bool>() ? 1 : 0;
        write_line(out, j);
    }
    if (isatty(STDERR_FILENO))
        std::fprintf(stderr, "umf-requester: %d frames, the field found in %d, %d unreadable\n", frames, found,
                     unreadable);
    return kOk;
}

}  // namespace umf::requester
