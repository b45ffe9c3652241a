// How the requester speaks of amounts, rates and waits on stderr: megabytes
// of 10^6 bytes with one decimal, as a transfer's progress and its end say
// them, and seconds.
#pragma once

#include <chrono>
#include <cstdint>
#include <string>

namespace umf::requester {

// "533.3 MB"
std::string megabytes(std::uint64_t bytes);

// "1073.7 MB in 1.52 s, 706.4 MB/s"
std::string transfer_rate(std::uint64_t bytes, std::chrono::steady_clock::duration took);

// "30 s", "2.5 s": a wait or a time-out.
std::string seconds_text(std::chrono::milliseconds ms);

}  // namespace umf::requester
