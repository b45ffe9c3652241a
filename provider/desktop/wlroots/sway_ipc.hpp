// Sway's IPC (the i3-ipc binary framing): "i3-ipc", a u32 payload length, a
// u32 message type (host byte order), then the JSON payload; the reply is
// framed the same way. One connection per request keeps it thread-safe.
#pragma once

#include <chrono>
#include <cstdint>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>

namespace umf::provider {

enum class SwayMessage : std::uint32_t {
    run_command = 0,
    get_outputs = 3,
    get_tree = 4,
    get_version = 7,
};

inline constexpr std::chrono::milliseconds kSwayTimeout{2000};

// The bytes of one request.
std::string sway_frame(SwayMessage type, const std::string& payload);

struct SwayHeader {
    std::uint32_t length = 0;
    std::uint32_t type = 0;
};
// The 14 bytes of a reply's header; nullopt without the magic.
std::optional<SwayHeader> parse_sway_header(const std::string& bytes);

// The reply's JSON; throws DesktopError when the socket does not answer in
// time, closes or answers nonsense.
nlohmann::json sway_request(const std::string& socket_path, SwayMessage type, const std::string& payload = {},
                            std::chrono::milliseconds timeout = kSwayTimeout);

// RUN_COMMAND: throws DesktopError with sway's own words when a command of
// `commands` failed.
void sway_run(const std::string& socket_path, const std::string& commands,
              std::chrono::milliseconds timeout = kSwayTimeout);

// The socket of the sway that runs now: `given` ($SWAYSOCK) when it answers,
// else one in `runtime_dir` named as sway names them (sway-ipc.UID.PID.sock)
// that does, for a provider started again after sway was (its environment
// still names the old socket). `given` when none answers.
std::string live_swaysock(const std::string& given, const std::string& runtime_dir);

}  // namespace umf::provider
