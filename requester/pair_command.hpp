// umf-requester pair: keep a screen's pairing (paired_screens.hpp), so grab
// and put find it without --url and can switch to it when it is the screen
// in view; list and forget the kept ones.
#pragma once

#include <cstdio>
#include <filesystem>
#include <string>

namespace umf::requester {

extern const char* const kPairUsage;

struct PairOptions {
    enum class Action { keep, list, forget } action = Action::keep;
    std::string what;  // keep: the pairing URL; forget: a name or URL
    std::filesystem::path file;
};

// argv[first..] of "umf-requester pair ...". Throws UsageError.
PairOptions parse_pair_args(int argc, char** argv, int first);

// Messages on stderr; returns kOk, kInputError (the list cannot be read or
// written), kConnection (the screen cannot be reached, or refused the
// pairing) or kNothing (forget: no such screen).
int run_pair(const PairOptions& options, std::FILE* out);

}  // namespace umf::requester
