// The commands' answers on stdout: one JSON object a line, its keys in the
// order they were set, written and flushed at once so that a program
// reading the pipe sees each line as it comes.
#pragma once

#include <cstdio>
#include <nlohmann/json.hpp>

namespace umf::requester {

using Json = nlohmann::ordered_json;

// Text that is not UTF-8 (a file name) is written with U+FFFD in its place.
// Throws InputError (cli.hpp) when the line cannot be written.
void write_line(std::FILE* out, const Json& j);

}  // namespace umf::requester
