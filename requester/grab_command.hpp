// umf-requester grab: point a camera (or a video, or one photo) at a
// provider's screen, find the field, and take what is shown under the image
// centre: a link is printed (and opened with --open), a file or snapshot is
// downloaded. The command line is the contract of docs/system.md; the one
// JSON line it prints at the end is what scripts read.
#pragma once

#include <cstdio>
#include <optional>
#include <string>

#include "requester/aiming_session.hpp"

namespace umf::requester {

extern const char* const kGrabUsage;

struct GrabOptions {
    PointingOptions pointing;
    std::optional<std::string> out;  // download directory; the desktop's default when empty
    bool open = false;               // open a link with xdg-open
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
