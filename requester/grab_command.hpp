// umf-requester grab: point a camera (or a video, or one photo) at a
// provider's screen, find the field, and take what is shown under the image
// centre: a link is printed (and opened with --open), a file or snapshot is
// downloaded. The command line is the contract of docs/system.md; the one
// JSON line it prints at the end is what scripts read.
#pragma once

#include <cstdio>
#include <optional>
#include <string>

#include "pairing_url.hpp"

namespace umf::requester {

extern const char* const kGrabUsage;

enum class GrabInput { camera, video, image };

struct GrabOptions {
    PairingUrl url;
    GrabInput input = GrabInput::camera;
    int camera_index = 0;
    std::string path;                // the video or image file
    std::optional<std::string> out;  // download directory; the desktop's default when empty
    bool open = false;               // open a link with xdg-open
    bool auto_grab = false;          // grab on a steady lock, no key needed
    bool window = false;             // show the preview (decided from --no-window and $DISPLAY)
    std::optional<double> timeout_s; // give up after this long (camera: 30 s by default)
};

// argv[first..] of "umf-requester grab ...". Throws UsageError.
GrabOptions parse_grab_args(int argc, char** argv, int first);

// Runs the grab, logs progress to stderr and writes exactly one JSON line
// to `out`; returns the exit code (cli.hpp: kOk, kInputError, kConnection,
// kNothing).
int run_grab(const GrabOptions& options, std::FILE* out);

// The JSON line for wrong usage, so scripts get a line even then.
void write_usage_failure(std::FILE* out, const std::string& message);

}  // namespace umf::requester
