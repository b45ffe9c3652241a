// umf-requester locate: where the camera looks on the field, for still
// images or the frames of a video, as one JSON line per frame. This is the
// contract outside benchmarks call our detector through (docs: system.md,
// "Command-line surface"): the keys and their order stay as specified; new
// keys only ever come after them.
#pragma once

#include <cstdio>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include <Eigen/Core>

#include "requester/cli.hpp"
#include "shared/overlay/preset.hpp"

namespace umf::requester {

extern const char* const kLocateUsage;

struct LocateOptions {
    std::string field_path;
    bool sequence = false;                 // consecutive frames: track (umf::Tracker)
    std::optional<Eigen::Vector2d> aim;    // image pixels; the image centre when empty
    std::vector<std::string> images;
    std::optional<std::string> video;
    // With sequence: the pulse the provider announces (its welcome's
    // overlay period, waveform and opacities), for the frames of a faint
    // field.
    std::optional<double> pulse_period_s;
    overlay::Waveform waveform = overlay::Waveform::sine;
    std::optional<std::pair<double, double>> pulse_opacities;  // min, max
};

// argv[first..] of "umf-requester locate ...". Throws UsageError.
LocateOptions parse_locate_args(int argc, char** argv, int first);

// Reads every frame, writes one JSON line per frame to `out` (flushed per
// line) and messages to stderr. Throws umf::FieldFileError for the field file
// and InputError for a video that cannot be opened or output that cannot be
// written; returns kOk otherwise, whatever the frames held.
int run_locate(const LocateOptions& options, std::FILE* out);

}  // namespace umf::requester
