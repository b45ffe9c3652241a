// umf_pulse_benchmark's command line: what it runs and with which of the
// pulse search's options (shared/detect/pulse_search.hpp), parsed from its
// arguments; --help prints the usage.
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include <opencv2/core.hpp>

namespace umf::bench {

struct PulseBenchmarkOptions {
    bool heldout = false;
    double min_opacity = 0.01, max_opacity = 0.04;
    int frames = 150;
    std::vector<cv::Size> resolutions{{640, 480}};
    bool announced = true;
    double frame_ms = 2;
    std::optional<double> max_motion_change;
    std::optional<double> max_follow_shape_change;
    double exposure_drift = 0;
    double readout_s = 0;
    int swing_speed = 1;
    std::optional<double> noise;
    std::optional<int> jpeg_quality;
    // A phone's local tone mapping on the tuning set's frames (sim::local_tone_map's strength; 0: none).
    double local_tone = 0;
    bool fit_gain = false;
    bool level_exposure = true;
    // The tuning set's optics: each frame's own draw; no smear, stripes or
    // lamp on any frame (plain); and the defocus the same on every frame
    // too (steady).
    enum class Optics { drawn, plain, steady };
    Optics optics = Optics::drawn;
    bool follow_carried = true;
    bool check_newest = true;
    std::optional<int> carry_frames;
    bool affine_coarse = false;
    bool affine_retry = true;
    bool detail_retry = true;
    std::optional<double> detail_carry_modules;
    bool field_alone = true;
    bool content_free = true;
    std::optional<double> max_share;
    std::optional<double> out_of_step_share;
    std::optional<int> kept_frames;  // PulseSearchOptions::frames
    std::optional<int> demodulation_level;  // PulseSearchOptions::demodulation_level
    std::vector<std::string> videos;  // empty: all
    std::string log;
    std::uint64_t seed = 1;
    int threads = 1;  // parse_pulse_options: all cores unless --threads
};

// Throws std::invalid_argument on a wrong option or value; --help prints
// the usage and exits.
PulseBenchmarkOptions parse_pulse_options(int argc, char** argv);

}  // namespace umf::bench
