// A put (docs/PROTOCOL.md, "Put") lands only when the person at the screen
// agrees. The service offers each put to a PutDecider and acts on its answer:
// the desktop prompt at the pointed place (put_prompt_window.hpp), the
// answers given through the control socket (`umf-provider puts`, for
// headless screens and scripts), or a fixed policy (`--puts always|never`).
#pragma once

#include <chrono>
#include <cstdint>
#include <filesystem>
#include <functional>
#include <optional>
#include <string>

#include "provider/content/resolver.hpp"
#include "shared/protocol/messages.hpp"

#include "provider/desktop/desktop.hpp"

namespace umf::provider {

struct PutOffer {
    std::uint64_t id = 0;          // provider-wide, unique while the provider runs
    std::string client;            // the hello's `client`, for the prompt
    std::string device;            // the hello's `device` (may be empty): "always accept from this device"
    protocol::ContentKind kind = protocol::ContentKind::file;  // url or file
    std::string title;             // what the requester calls it (may be empty)
    std::string url;               // kind url
    std::string name, mime;        // kind file: the safe file name and type
    std::int64_t size = 0;         // kind file, bytes
    std::optional<ScreenPoint> at; // where the phone points, when a screen shows the point
};

enum class PutAnswer {
    save,     // file: saved in the put folder; url: opened in the default browser
    open,     // file: saved, then opened with the desktop's default application; url: as save
    dismiss,  // refused
};

struct PutReply {
    PutAnswer answer = PutAnswer::dismiss;
    // Remember: accept this device's puts without asking, its files saved or
    // opened as this answer says (trusted_devices.hpp).
    bool always_from_device = false;
};

class PutDecider {
public:
    virtual ~PutDecider() = default;
    // Called on a server thread; must not block. `answer` may be called later,
    // from any thread, at most once; a second call is ignored.
    virtual void ask(const PutOffer& offer, std::function<void(PutReply)> answer) = 0;
    // The offer ended without an answer (it timed out, the requester left):
    // take its prompt down. Called on any thread.
    virtual void withdraw(std::uint64_t id) = 0;
};

struct PutSettings {
    std::filesystem::path folder;                 // where files land (the XDG download folder by default)
    std::int64_t max_bytes = std::int64_t{4} << 30;  // larger files are refused with too_large
    // Milliseconds so tests can wait a fraction of a second; std::chrono::seconds still assign.
    std::chrono::milliseconds answer_timeout{30'000};  // then the offer is dismissed
    std::chrono::milliseconds upload_ttl{60'000};      // an accepted file's upload link
    // The devices whose puts are accepted without asking ("always from this
    // device"), kept across runs: normally <config dir>/trusted-devices.json
    // (kTrustedDevicesFile). Empty: remembered only while the provider runs.
    std::filesystem::path trusted_devices;
    // How an opened put's window is moved to the pointed place: the
    // desktop's (Desktop::watch_new_window); empty or nullptr: not moved.
    std::function<std::unique_ptr<NewWindowWatch>(const WindowPlacement&)> watch_new_window;
    // Opens a URL put at a point in the application shown there (a new tab
    // in the browser window pointed at, through the browser companion); false
    // when nothing there can, and xdg-open opens it. Empty: always xdg-open.
    std::function<bool(const ScreenPoint&, const std::string& url)> open_url_at;
};

}  // namespace umf::provider
