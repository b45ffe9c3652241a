// The provider's answers to requester messages, independent of sockets (so
// unit tests drive it directly): docs/PROTOCOL.md, "Session". The transport
// (net/) reaches it as a MessageHandler: each session's Conversation
// (service_conversation.cpp) holds a SessionState and calls handle_text or
// handle_binary per received message; `close` in the Replies says to end the
// session after sending them.
#pragma once

#include <array>
#include <atomic>
#include <chrono>
#include <functional>
#include <map>
#include <memory>
#include <mutex>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "provider/common/activity.hpp"
#include "provider/content/download_table.hpp"
#include "provider/content/file_facts.hpp"
#include "provider/content/resolver.hpp"
#include "provider/discovery/nearby_screens.hpp"
#include "provider/net/message_handler.hpp"
#include "provider/put/put_decision.hpp"
#include "provider/put/put_desk.hpp"
#include "provider/screen/desktop_layout.hpp"
#include "provider/service/rate_limit.hpp"
#include "provider/service/static_site.hpp"
#include "shared/overlay/placement.hpp"
#include "shared/overlay/preset.hpp"
#include "shared/protocol/messages.hpp"

namespace umf::provider {

// The field and where each screen shows it. A service keeps one at a time
// and replaces it whole when the screens change (Service::set_screens).
struct ScreenMap {
    protocol::FieldInfo field;
    // Where the field lies on each of field.screens, in the same order, and
    // where each screen's top-left corner is on the desktop (X11 root window).
    std::vector<overlay::FieldPlacement> placements;
    std::vector<std::array<int, 2>> desktop_offsets;
    std::uint64_t generation = 0;  // counts the replacements
};

ScreenMap screen_map_for(const DesktopLayout& layout);

struct ServiceConfig {
    protocol::ProviderInfo provider;
    ScreenMap screens;  // the first; Service::screens() has the current one
    protocol::OverlayInfo overlay;
    protocol::Limits limits;
    // Files above this are refused with too_large.
    std::int64_t max_download_bytes = std::int64_t{16} << 30;
    // Kiosks: any token is welcome; the resolvers (chosen by whoever builds
    // the Service) are the board's only.
    bool public_mode = false;
    // Puts (docs/PROTOCOL.md, "Put"): who decides at the screen. Null: no
    // puts; the welcome names no "put" feature and a put is refused.
    std::shared_ptr<PutDecider> put_decider;
    PutSettings puts;
    // The other screens announced nearby (/nearby.json); null: none.
    std::shared_ptr<const NearbyScreens> nearby;
};

// The screens and the field of a desktop layout, the `balanced` preset, the
// protocol's default limits and this host's name.
ServiceConfig service_config_for(const DesktopLayout& layout);
// What the welcome says of a preset: the protocol's own description of it.
protocol::OverlayInfo overlay_info(const overlay::Preset& preset);

// The same for one screen of the given size at the desktop's origin, with
// modules of module_px (0: the size that covers the screen). Throws when the
// field file cannot be loaded.
ServiceConfig default_service_config(int screen_width_px = 1920, int screen_height_px = 1080,
                                     const std::string& screen_name = "screen", double module_px = 0.0,
                                     const FieldSource& fields = {});

// What one connection has established so far, and its rate limits.
struct SessionState {
    bool welcomed = false;
    std::uint64_t id = 0;  // given at the welcome; for the activity listener
    std::string peer;  // the remote address, for per-address limits on wrong tokens
    TokenBucket aims;
    TokenBucket grabs;
    std::optional<SteadyTime> last_rate_error;  // when dropped aims were last reported
    std::uint64_t screens_generation = 0;       // the ScreenMap its welcome described
    std::string client;  // the hello's, for the screen's put prompt
    std::string device;  // the hello's `device`, empty when none
    // The pairing token its hello proved: its download links ask for it
    // (docs/PROTOCOL.md, "Downloads"). Empty in public mode.
    std::string token;
    // Where the provider's own messages for this session go (a put's answer
    // comes later, on any thread): set by the connection before the hello,
    // called with the session's id and an encoded message; must not block.
    // Unset: the session hears nothing pushed.
    std::function<void(std::uint64_t session, std::string encoded_message)> outbox;
};

// The service's answer to one frame: the messages to send, in order, and
// what then becomes of the connection.
struct Replies {
    std::vector<protocol::Message> replies;
    bool close = false;  // close the WebSocket (policy violation, 1008) after sending the replies
    // With close: 1012 (service restart) instead, for a session whose welcome
    // no longer describes the screens; the requester connects again.
    bool restart = false;
};

// Wrong tokens an address may send within kWrongTokenWindow before its
// hellos are refused unread for the rest of that window.
inline constexpr int kMaxWrongTokens = 5;
inline constexpr std::chrono::seconds kWrongTokenWindow{60};

class Service : public MessageHandler, public std::enable_shared_from_this<Service> {
public:
    // Resolvers are asked in order. No site: the built-in page.
    // The activity listener hears of every seeking, aim and session end.
    Service(ServiceConfig config, std::string token, std::vector<std::shared_ptr<const Resolver>> resolvers = {},
            std::shared_ptr<const StaticSite> site = nullptr, std::shared_ptr<ActivityListener> activity = nullptr);

    // One text frame. Before the welcome: a hello with the token gets the
    // welcome, anything else an error and `close`. After it: seeking gets
    // nothing, aim a target, grab a content, anything malformed or not a
    // request an error; the session is never closed.
    Replies handle_text(SessionState& state, std::string_view text, SteadyTime now = std::chrono::steady_clock::now()) const;
    // A binary frame: bad_request (and `close` before the welcome).
    Replies handle_binary(SessionState& state) const;
    // A parsed frame (what handle_text does after parsing).
    Replies handle(SessionState& state, const protocol::ParseResult& parsed,
                   SteadyTime now = std::chrono::steady_clock::now()) const;

    // The screen point a field point lies on, or nullopt when no screen
    // shows it.
    std::optional<ScreenPoint> screen_point(protocol::FieldPoint point) const;
    // What the resolvers find at a field point, first answer wins; kind none
    // when nothing. Throws what a resolver throws.
    Resolved resolve(const ScreenPoint& point, Purpose purpose) const;

    // Hashes these files in the background (a board's), so their first grabs
    // carry a SHA-256 and wait for nothing.
    void prepare_files(const std::vector<std::filesystem::path>& files) const;
    // A download found a file's bytes not matching its hash: the next grab
    // hashes it again.
    void forget_file(const std::filesystem::path& file) const;

    // A session ends (its conversation calls this once, welcomed or not).
    void session_ended(const SessionState& state) const;

    // MessageHandler, for the transport. A conversation holds the service
    // (open needs it held by a shared_ptr) and encodes the replies.
    std::unique_ptr<Conversation> open(std::string peer, Push push) const override;
    std::uint64_t screens_generation() const override { return screens()->generation; }
    std::size_t max_message_bytes() const override;

    // Replaces the token; sessions already welcomed stay.
    void set_token(std::string token);
    // The screens changed (one came, went or changed size or density): new
    // sessions get the new field in their welcome, and a session welcomed
    // before is closed with 1012 at its next request, since its field points
    // would land elsewhere now. Throws std::invalid_argument for a layout
    // without screens.
    void set_screens(const DesktopLayout& layout);
    std::shared_ptr<const ScreenMap> screens() const;
    // Calls `on_change` after each set_screens (on that caller's thread, the
    // new map in place) for as long as the returned handle is held; it must
    // not block. The HTTPS transport answers open polls with it.
    std::shared_ptr<void> watch_screens(std::function<void()> on_change) const override;
    const ServiceConfig& config() const { return config_; }
    DownloadTable& downloads() const { return *downloads_; }
    // Puts: offers, their answers pushed to sessions, the upload links.
    PutDesk& puts() const { return *puts_; }
    const StaticSite& site() const { return *site_; }

private:
    bool token_matches(std::string_view token) const;
    Replies hello(SessionState& state, const protocol::Hello& hello, SteadyTime now) const;
    std::optional<protocol::Message> aim(SessionState& state, const protocol::Aim& aim, SteadyTime now) const;
    // Nullopt when the answer comes later through the session's outbox (a
    // large file being hashed).
    std::optional<protocol::Message> grab(SessionState& state, const protocol::Grab& grab, SteadyTime now) const;
    protocol::Message put(SessionState& state, const protocol::Put& put, SteadyTime now) const;

    ServiceConfig config_;  // its screens are the first; screens_ holds the current
    mutable std::mutex screens_mutex_;
    std::shared_ptr<const ScreenMap> screens_;
    mutable std::mutex watchers_mutex_;
    mutable std::vector<std::weak_ptr<std::function<void()>>> screen_watchers_;
    std::vector<std::shared_ptr<const Resolver>> resolvers_;
    std::shared_ptr<DownloadTable> downloads_;
    std::shared_ptr<PutDesk> puts_;
    std::shared_ptr<FileFactsCache> facts_;
    std::shared_ptr<const StaticSite> site_;
    std::shared_ptr<ActivityListener> activity_;
    mutable std::atomic<std::uint64_t> next_session_{1};
    mutable std::mutex token_mutex_;
    std::string token_;
    struct WrongTokens {
        int count = 0;
        SteadyTime since{};
    };
    mutable std::mutex wrong_mutex_;
    mutable std::map<std::string, WrongTokens> wrong_tokens_;
};

}  // namespace umf::provider
