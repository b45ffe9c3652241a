#include "tests/bench/pulse_benchmark_options.hpp"

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <sstream>
#include <stdexcept>
#include <thread>

#include "shared/detect/pulse_search.hpp"
#include "tests/bench/methods.hpp"
#include "tests/sim/sequence.hpp"

namespace umf::bench {
namespace {

const char* const kUsage = R"(umf_pulse_benchmark: a field pulsing at a few percent found over a hand-held phone's frames.

Usage: umf_pulse_benchmark [options]
  --set tuning|heldout   whose pulsing videos (default tuning): the tuning set's swing from looking up at the
                         screen to looking down on it at 25 fps, one video per screen kind; or the held-out
                         set's hand path at 30 fps, one per content, on its three screens and camera model
  --opacities MIN,MAX    the pulse's opacities (default 0.01,0.04), sine, every 1.5 s
  --frames N             frames per video (default 150)
  --resolutions WxH,...  (default 640x480)
  --kept-frames N        the frames the pulse search keeps and demodulates together (default 24)
  --demodulation-level L a place carried followed first in the frames demodulated at level L of their pyramid:
                         0 not, 1 half size, 2 a quarter (PulseSearchOptions::demodulation_level; default: the
                         library's)
  --not-announced        the pulse search is not told the pulse's period, waveform and opacities
  --frame-ms MS          the tracker's search held to MS a frame, as the page holds it (TrackerOptions::frame_ms
                         with its spread search; default 2); 0: every search on every frame without a lock
  --max-motion-change X  PulseSearchOptions::max_motion_change (default: the library's)
  --max-follow-shape-change X
                         PulseSearchOptions::max_follow_shape_change, modules (default: the library's; 1e9:
                         a follow's map always carried on)
  --exposure-drift A     the tuning set's videos with an auto-exposure that drifts and re-meters, the light
                         scaled by up to about 1 +- A from frame to frame (default 0: a steady exposure)
  --rolling-shutter S    the tuning set's videos read row by row over S seconds (first row to last, the
                         middle row at the frame's own pose), the camera moving on towards the next frame's
                         pose meanwhile (default 0: every row at once)
  --swing-speed K        the tuning set's hand swinging K times as fast (an integer; default 1)
  --noise S              the tuning set's sensor noise, S grey levels (default: 2 to 3 a frame)
  --jpeg-quality Q       the tuning set's frames encoded at JPEG quality Q (default 80)
  --local-tone S         the tuning set's frames through a phone's local tone mapping of strength S (0 to 1; each
                         pixel scaled by the frame's mean over the mean around it, to the power S; default 0), as
                         the held-out set's camera does at 0 to 0.5
  --plain-optics         the tuning set's frames without the smear, the screen's stripes and the lamp that
                         some frames have at random (each frame's defocus still its own, 0.5 to 1.5 px)
  --steady-optics        as --plain-optics, and every frame defocused by the same 1 px
  --gain                 the frames registered with the exposure's gain as well as a grey-level offset
                         (RegistrationOptions::fit_gain)
  --no-levelling         the frames laid onto the newest not levelled to its exposure before demodulating
                         (PulseSearchOptions::level_exposure off)
  --carry-frames N       PulseSearchOptions::carry_frames (default: the library's)
  --max-share X          RegistrationOptions::max_share (default: the library's)
  --out-of-step-share X  PulseSearchOptions::out_of_step_share (default: the library's)
  --affine-coarse        every registration's coarsest level an affine change
                         (RegistrationOptions::affine_coarse on)
  --no-affine-retry      no registration tried again with an affine coarsest level
                         (PulseSearchOptions::affine_retry off)
  --no-detail-retry      no registration tried again on the frames' detail
                         (PulseSearchOptions::detail_retry off)
  --detail-carry-modules X
                         PulseSearchOptions::detail_carry_modules (default: the library's)
  --no-field-alone       the field alone not looked for where the slope image fails
                         (PulseSearchOptions::field_alone off)
  --no-content-free      the slope with the content's leakage taken out not looked
                         in where the others fail (PulseSearchOptions::content_free_tile 0)
  --no-follow            a place carried not looked for where it is said to be before each search
                         (PulseSearchOptions::follow_carried off)
  --no-newest-check      a place the pulse search gives not checked in the newest frame alone
                         (PulseSearchOptions::check_newest off)
  --videos a,b           only these videos (screen kinds, or held-out contents; the tuning set's spreadsheet
                         only when named)
  --log FILE             one line per frame of the pulse search's videos: video, frame, state, where the
                         place came from, its error in modules, the share the pulse explained where searched,
                         ms, and the frame's registration onto the last: registered, residual, the residual
                         unmoved, overlap, whether aligned on the frames' detail, the residual where the
                         motion guessed laid the frames, and (tuning set) how far the registration put the
                         frame's centre from the true motion's, pixels; then the place carried: frames since
                         it was found or confirmed, and the modules the aim has come over the field since; and
                         where the pulse search gave the place, its check in the frame alone (field_shift.hpp):
                         the shift the frame's own field shows (x, y pixels), the evidence there, at the place
                         and from the content alone (FieldShift), the module's size in pixels, and the place's
                         true error at the aim (x, y pixels)
  --seed N               scenario seed (default 1)
  --threads N            threads making frames (default: all cores)
  --help                 this text

Every video is also run without the field (the same frames, opacity 0): every place found there is wrong.
A place is right within half a module of the truth. Times are of one update on one thread: the tracker,
laying the frame onto the last and, where it ran, the search of the frames together.
Progress goes to stderr, the tables to stdout.
)";

}  // namespace

PulseBenchmarkOptions parse_pulse_options(int argc, char** argv) {
    PulseBenchmarkOptions o;
    o.threads = static_cast<int>(std::max(1u, std::thread::hardware_concurrency()));
    for (int i = 1; i < argc; ++i) {
        const std::string a = argv[i];
        const auto value = [&]() -> std::string {
            if (i + 1 >= argc) throw std::invalid_argument(a + " needs a value");
            return argv[++i];
        };
        if (a == "--help") {
            std::fputs(kUsage, stdout);
            std::exit(0);
        } else if (a == "--set") {
            const std::string s = value();
            if (s != "tuning" && s != "heldout") throw std::invalid_argument("--set: tuning or heldout, not " + s);
            o.heldout = s == "heldout";
        } else if (a == "--opacities") {
            if (std::sscanf(value().c_str(), "%lf,%lf", &o.min_opacity, &o.max_opacity) != 2 || !(o.min_opacity >= 0) ||
                !(o.max_opacity > o.min_opacity) || o.max_opacity > 1)
                throw std::invalid_argument("--opacities: MIN,MAX with 0 <= MIN < MAX <= 1");
        } else if (a == "--frames") {
            o.frames = std::stoi(value());
            if (o.frames < 1) throw std::invalid_argument("--frames: at least 1");
        } else if (a == "--resolutions") {
            o.resolutions = parse_resolutions(value());
        } else if (a == "--frame-ms") {
            o.frame_ms = std::stod(value());
            if (!(o.frame_ms >= 0)) throw std::invalid_argument("--frame-ms: 0 or more");
        } else if (a == "--kept-frames") {
            o.kept_frames = std::stoi(value());
            // Fewer than the search waits for, it would never search: the
            // table would show the tracker alone under the pulse search's name.
            if (*o.kept_frames < PulseSearchOptions{}.min_frames)
                throw std::invalid_argument("--kept-frames: at least " +
                                            std::to_string(PulseSearchOptions{}.min_frames));
        } else if (a == "--demodulation-level") {
            o.demodulation_level = std::stoi(value());
            if (*o.demodulation_level < 0 || *o.demodulation_level > 2)
                throw std::invalid_argument("--demodulation-level: 0, 1 or 2");
        } else if (a == "--not-announced") {
            o.announced = false;
        } else if (a == "--max-motion-change") {
            o.max_motion_change = std::stod(value());
        } else if (a == "--max-follow-shape-change") {
            o.max_follow_shape_change = std::stod(value());
        } else if (a == "--exposure-drift") {
            o.exposure_drift = std::stod(value());
            if (!(o.exposure_drift >= 0 && o.exposure_drift < 0.5)) throw std::invalid_argument("--exposure-drift: 0 to 0.5");
        } else if (a == "--rolling-shutter") {
            o.readout_s = std::stod(value());
            if (!(o.readout_s >= 0 && o.readout_s < 1 / sim::kFps))
                throw std::invalid_argument("--rolling-shutter: 0 to one frame's interval (0.04 s)");
        } else if (a == "--swing-speed") {
            o.swing_speed = std::stoi(value());
            if (o.swing_speed < 1 || o.swing_speed > 8) throw std::invalid_argument("--swing-speed: 1 to 8");
        } else if (a == "--local-tone") {
            o.local_tone = std::stod(value());
            if (!(o.local_tone >= 0 && o.local_tone <= 1)) throw std::invalid_argument("--local-tone: 0 to 1");
        } else if (a == "--noise") {
            o.noise = std::stod(value());
            if (!(*o.noise >= 0 && *o.noise <= 30)) throw std::invalid_argument("--noise: 0 to 30 grey levels");
        } else if (a == "--jpeg-quality") {
            o.jpeg_quality = std::stoi(value());
            if (*o.jpeg_quality < 1 || *o.jpeg_quality > 100) throw std::invalid_argument("--jpeg-quality: 1 to 100");
        } else if (a == "--gain") {
            o.fit_gain = true;
        } else if (a == "--carry-frames") {
            o.carry_frames = std::stoi(value());
            if (*o.carry_frames < 0) throw std::invalid_argument("--carry-frames: 0 or more");
        } else if (a == "--max-share") {
            o.max_share = std::stod(value());
        } else if (a == "--out-of-step-share") {
            o.out_of_step_share = std::stod(value());
            if (!(*o.out_of_step_share >= 0 && *o.out_of_step_share <= 1))
                throw std::invalid_argument("--out-of-step-share: 0 to 1");
        } else if (a == "--affine-coarse") {
            o.affine_coarse = true;
        } else if (a == "--no-affine-retry") {
            o.affine_retry = false;
        } else if (a == "--no-detail-retry") {
            o.detail_retry = false;
        } else if (a == "--detail-carry-modules") {
            o.detail_carry_modules = std::stod(value());
            if (!(*o.detail_carry_modules >= 0)) throw std::invalid_argument("--detail-carry-modules: 0 or more");
        } else if (a == "--no-field-alone") {
            o.field_alone = false;
        } else if (a == "--no-content-free") {
            o.content_free = false;
        } else if (a == "--no-follow") {
            o.follow_carried = false;
        } else if (a == "--no-newest-check") {
            o.check_newest = false;
        } else if (a == "--plain-optics") {
            o.optics = PulseBenchmarkOptions::Optics::plain;
        } else if (a == "--steady-optics") {
            o.optics = PulseBenchmarkOptions::Optics::steady;
        } else if (a == "--no-levelling") {
            o.level_exposure = false;
        } else if (a == "--videos") {
            std::stringstream list(value());
            for (std::string name; std::getline(list, name, ',');) o.videos.push_back(name);
        } else if (a == "--log") {
            o.log = value();
        } else if (a == "--seed") {
            o.seed = std::stoull(value());
        } else if (a == "--threads") {
            o.threads = std::max(1, std::stoi(value()));
        } else {
            throw std::invalid_argument("unknown option " + a + " (--help lists them)");
        }
    }
    return o;
}

}  // namespace umf::bench
