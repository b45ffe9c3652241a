// umf-requester put: point a camera (or a video, or one photo) at a
// provider's screen and give it a file or a URL at the pointed place. The
// person at the screen accepts or refuses; an accepted file goes up over its
// one-time HTTPS link. One JSON line at the end, like grab.
#pragma once

#include <cstdio>
#include <filesystem>
#include <optional>
#include <string>

#include "requester/aiming_session.hpp"

namespace umf::requester {

extern const char* const kPutUsage;

struct PutOptions {
    PointingOptions pointing;
    std::optional<std::string> url;              // put a link ...
    std::optional<std::filesystem::path> file;   // ... or a file
    std::string title;                           // shown in the prompt; may be empty
    std::filesystem::path device_file;           // where this device's name is kept
};

// argv[first..] of "umf-requester put ...". Throws UsageError.
PutOptions parse_put_args(int argc, char** argv, int first);

// Runs the put, logs progress to stderr and writes exactly one JSON line to
// `out`; returns the exit code (kOk, kInputError, kConnection, kNothing).
int run_put(const PutOptions& options, std::FILE* out);

}  // namespace umf::requester
