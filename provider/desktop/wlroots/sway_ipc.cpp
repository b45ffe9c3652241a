#include "provider/desktop/wlroots/sway_ipc.hpp"

#include <cstring>
#include <filesystem>

#include "provider/desktop/desktop.hpp"
#include "provider/desktop/wlroots/unix_socket.hpp"

namespace umf::provider {

namespace {

constexpr char kMagic[] = {'i', '3', '-', 'i', 'p', 'c'};
constexpr std::size_t kHeaderSize = sizeof kMagic + 8;
// A tree of thousands of windows is a few MB; more is not an answer.
constexpr std::uint32_t kMaxReply = 64u << 20;

}  // namespace

std::string sway_frame(SwayMessage type, const std::string& payload) {
    std::string out(kMagic, sizeof kMagic);
    const auto length = static_cast<std::uint32_t>(payload.size());
    const auto code = static_cast<std::uint32_t>(type);
    out.append(reinterpret_cast<const char*>(&length), 4);
    out.append(reinterpret_cast<const char*>(&code), 4);
    return out + payload;
}

std::optional<SwayHeader> parse_sway_header(const std::string& bytes) {
    if (bytes.size() < kHeaderSize || std::memcmp(bytes.data(), kMagic, sizeof kMagic) != 0) return std::nullopt;
    SwayHeader header;
    std::memcpy(&header.length, bytes.data() + sizeof kMagic, 4);
    std::memcpy(&header.type, bytes.data() + sizeof kMagic + 4, 4);
    return header;
}

nlohmann::json sway_request(const std::string& socket_path, SwayMessage type, const std::string& payload,
                            std::chrono::milliseconds timeout) {
    UnixSocket socket(socket_path, std::chrono::steady_clock::now() + timeout);
    socket.write_all(sway_frame(type, payload));
    const auto header = parse_sway_header(socket.read_exact(kHeaderSize));
    if (!header) throw DesktopError("sway's IPC answered without the i3-ipc header");
    if (header->length > kMaxReply) throw DesktopError("sway's IPC announced an oversized reply");
    const std::string body = socket.read_exact(header->length);
    auto json = nlohmann::json::parse(body, nullptr, false);
    if (json.is_discarded()) throw DesktopError("sway's IPC answered with malformed JSON");
    return json;
}

void sway_run(const std::string& socket_path, const std::string& commands, std::chrono::milliseconds timeout) {
    const auto reply = sway_request(socket_path, SwayMessage::run_command, commands, timeout);
    if (!reply.is_array()) throw DesktopError("sway answered '" + commands + "' with no list of results");
    for (const auto& result : reply)
        if (!result.value("success", false))
            throw DesktopError("sway refused '" + commands + "': " + result.value("error", std::string("no reason")));
}

std::string live_swaysock(const std::string& given, const std::string& runtime_dir) {
    const auto answers = [](const std::string& path) {
        try {
            sway_request(path, SwayMessage::get_version, {}, std::chrono::milliseconds(500));
            return true;
        } catch (const DesktopError&) {
            return false;
        }
    };
    if (given.empty() || answers(given)) return given;
    std::error_code ec;
    for (const auto& entry : std::filesystem::directory_iterator(runtime_dir, ec)) {
        const std::string name = entry.path().filename().string();
        if (name.rfind("sway-ipc.", 0) == 0 && name.size() > 5 && name.compare(name.size() - 5, 5, ".sock") == 0 &&
            entry.is_socket(ec) && answers(entry.path().string()))
            return entry.path().string();
    }
    return given;
}

}  // namespace umf::provider
