#include "provider/service/service.hpp"

#include <cstdio>
#include <stdexcept>
#include <type_traits>

#include "provider/common/screen_name.hpp"
#include "provider/service/pairing.hpp"
#include "shared/overlay/preset.hpp"

#ifndef UMF_PROVIDER_VERSION
#define UMF_PROVIDER_VERSION "0.0.0"
#endif

namespace umf::provider {

namespace p = protocol;

namespace {

std::string point_text(p::FieldPoint point) {
    char text[96];
    std::snprintf(text, sizeof text, "[%.2f, %.2f]", point.u, point.v);
    return text;
}

// Aims may come in short bursts (a requester catching up after a stall);
// grabs up to a fifth of a minute's allowance at once.
TokenBucket aim_bucket(const p::Limits& limits) { return {limits.aims_per_s, std::max(1.0, limits.aims_per_s)}; }
TokenBucket grab_bucket(const p::Limits& limits) {
    return {limits.grabs_per_min / 60.0, std::max(1.0, limits.grabs_per_min / 5.0)};
}

p::Error unreadable(const p::Grab& grab, const Resolved& resolved) {
    return p::Error{grab.id, p::ErrorCode::internal, "cannot read " + p::safe_file_name(resolved.name)};
}

// The content message for what a grab resolved, a file's download link
// registered; `facts` is the resolved file's (null for a URL or bytes).
p::Message content_for(const p::Grab& grab, const Resolved& resolved, const FileFacts* facts, DownloadTable& downloads,
                       std::int64_t max_download_bytes, const std::string& token) {
    p::Content c;
    c.id = grab.id;
    c.kind = resolved.kind;
    c.title = resolved.title;
    switch (resolved.kind) {
        case p::ContentKind::none:
            break;
        case p::ContentKind::url:
            c.url = resolved.url;
            break;
        case p::ContentKind::file:
        case p::ContentKind::snapshot: {
            DownloadEntry entry;
            entry.name = p::safe_file_name(resolved.name);
            entry.mime = resolved.mime.empty() ? "application/octet-stream" : resolved.mime;
            if (resolved.file && facts) {
                entry.size = facts->size;
                entry.sha256 = facts->sha256;
                entry.identity = facts->identity;
                entry.leased_ctime_ns = facts->leased_ctime_ns;
                entry.file = resolved.file;
            } else if (resolved.bytes) {
                entry.size = static_cast<std::int64_t>(resolved.bytes->size());
                entry.sha256 = sha256_hex(*resolved.bytes);
                entry.bytes = resolved.bytes;
            } else {
                return p::Error{grab.id, p::ErrorCode::internal, "the content under the point has no data"};
            }
            if (entry.size > max_download_bytes)
                return p::Error{grab.id, p::ErrorCode::too_large,
                                entry.name + " is " + std::to_string(entry.size) + " bytes, more than the limit of " +
                                    std::to_string(max_download_bytes)};
            c.name = entry.name;
            c.mime = entry.mime;
            c.size = entry.size;
            c.sha256 = entry.sha256;
            entry.token = token;
            c.download = downloads.add(std::move(entry));
            break;
        }
    }
    return c;
}

// content_for, and the activity listener told of what was grabbed.
p::Message answer_grab(std::uint64_t session, const std::string& token, const p::Grab& grab, const Resolved& resolved,
                       const FileFacts* facts, DownloadTable& downloads, std::int64_t max_download_bytes,
                       ActivityListener* activity) {
    p::Message reply = content_for(grab, resolved, facts, downloads, max_download_bytes, token);
    if (const auto* c = std::get_if<p::Content>(&reply); c && activity)
        activity->grabbed({session, c->kind, c->title, c->name.value_or(""), c->size.value_or(0)});
    return reply;
}

}  // namespace

ScreenMap screen_map_for(const DesktopLayout& layout) {
    ScreenMap m;
    m.field.definition = layout.field;
    for (const auto& laid : layout.screens) {
        p::Screen screen;
        screen.name = laid.screen.name;
        screen.region = {laid.region.u0, laid.region.v0, laid.region.u1, laid.region.v1};
        screen.width_px = laid.screen.width;
        screen.height_px = laid.screen.height;
        m.field.screens.push_back(screen);
        m.placements.push_back(laid.field.placement);
        m.desktop_offsets.push_back({laid.screen.x, laid.screen.y});
    }
    return m;
}

ServiceConfig service_config_for(const DesktopLayout& layout) {
    ServiceConfig c;
    c.provider.name = screen_name();
    c.provider.software = std::string("umf-provider/") + UMF_PROVIDER_VERSION;
    c.screens = screen_map_for(layout);
    const auto presets = overlay::built_in_presets();
    const overlay::Preset* balanced = overlay::find_preset(presets, "balanced");
    if (!balanced) throw std::logic_error("the built-in preset \"balanced\" is missing");
    c.overlay = overlay_info(*balanced);
    c.limits = p::Limits{};
    return c;
}

// The wire's limits are the presets' own.
static_assert(p::kMaxOverlayNameBytes == overlay::kMaxPresetNameBytes);
static_assert(p::kMinPulsePeriodS == overlay::kMinPeriodS && p::kMaxPulsePeriodS == overlay::kMaxPeriodS);

protocol::OverlayInfo overlay_info(const overlay::Preset& preset) {
    return {preset.name, preset.opacity_min, preset.opacity_max, preset.period_s,
            preset.waveform == overlay::Waveform::triangle ? p::PulseWaveform::triangle : p::PulseWaveform::sine};
}

ServiceConfig default_service_config(int screen_width_px, int screen_height_px, const std::string& screen_name,
                                     double module_px, const FieldSource& fields) {
    return service_config_for(
        lay_out_desktop({{screen_name, 0, 0, screen_width_px, screen_height_px, module_px}}, fields));
}

Service::Service(ServiceConfig config, std::string token, std::vector<std::shared_ptr<const Resolver>> resolvers,
                 std::shared_ptr<const StaticSite> site, std::shared_ptr<ActivityListener> activity)
    : config_(std::move(config)),
      resolvers_(std::move(resolvers)),
      downloads_(std::make_shared<DownloadTable>(std::chrono::milliseconds(
          static_cast<std::int64_t>(config_.limits.download_ttl_s * 1000.0)))),
      puts_(PutDesk::create(config_.put_decider, config_.puts, activity)),
      facts_(std::make_shared<FileFactsCache>()),
      site_(site ? std::move(site) : std::make_shared<const StaticSite>()),
      activity_(std::move(activity)),
      token_(std::move(token)) {
    ScreenMap& first = config_.screens;
    if (first.placements.size() != first.field.screens.size() || first.field.screens.empty())
        throw std::invalid_argument("a service needs screens, with one field placement each");
    first.desktop_offsets.resize(first.placements.size(), {0, 0});
    screens_ = std::make_shared<const ScreenMap>(first);
    // What a put opens is placed on the pointed screen; the desk lives no
    // longer than this service.
    puts_->set_screen_rects([this](int index) -> std::optional<PlaceRect> {
        const auto map = screens();
        if (index < 0 || static_cast<std::size_t>(index) >= map->field.screens.size()) return std::nullopt;
        const auto& screen = map->field.screens[index];
        const auto& offset = map->desktop_offsets[index];
        return PlaceRect{offset[0], offset[1], screen.width_px, screen.height_px};
    });
}

void Service::set_screens(const DesktopLayout& layout) {
    ScreenMap next = screen_map_for(layout);
    if (next.field.screens.empty()) throw std::invalid_argument("a service needs screens");
    {
        std::lock_guard lock(screens_mutex_);
        next.generation = screens_->generation + 1;
        screens_ = std::make_shared<const ScreenMap>(std::move(next));
    }
    std::vector<std::shared_ptr<std::function<void()>>> watchers;
    {
        std::lock_guard lock(watchers_mutex_);
        std::erase_if(screen_watchers_, [&](const auto& weak) {
            auto watcher = weak.lock();
            if (watcher) watchers.push_back(std::move(watcher));
            return !watcher;
        });
    }
    for (const auto& watcher : watchers) (*watcher)();
}

std::shared_ptr<void> Service::watch_screens(std::function<void()> on_change) const {
    auto watcher = std::make_shared<std::function<void()>>(std::move(on_change));
    std::lock_guard lock(watchers_mutex_);
    std::erase_if(screen_watchers_, [](const auto& weak) { return weak.expired(); });
    screen_watchers_.push_back(watcher);
    return watcher;
}

std::shared_ptr<const ScreenMap> Service::screens() const {
    std::lock_guard lock(screens_mutex_);
    return screens_;
}

void Service::prepare_files(const std::vector<std::filesystem::path>& files) const { facts_->prepare(files); }

void Service::forget_file(const std::filesystem::path& file) const { facts_->forget(file); }

void Service::session_ended(const SessionState& state) const {
    if (!state.welcomed) return;
    puts_->session_ended(state.id);
    if (activity_) activity_->left(state.id);
}

void Service::set_token(std::string token) {
    std::lock_guard lock(token_mutex_);
    token_ = std::move(token);
}

bool Service::token_matches(std::string_view token) const {
    std::lock_guard lock(token_mutex_);
    return !token_.empty() && tokens_equal(token, token_);
}

std::optional<ScreenPoint> Service::screen_point(p::FieldPoint point) const {
    const std::shared_ptr<const ScreenMap> map = screens();
    const auto& screens = map->field.screens;
    for (std::size_t i = 0; i < screens.size(); ++i) {
        const p::FieldRect& r = screens[i].region;
        if (point.u < r.u0 || point.u >= r.u1 || point.v < r.v0 || point.v >= r.v1) continue;
        const overlay::PixelPoint s = overlay::field_to_screen(map->placements[i], point.u, point.v);
        ScreenPoint out;
        out.screen = static_cast<int>(i);
        out.x = s.x;
        out.y = s.y;
        out.root_x = s.x + map->desktop_offsets[i][0];
        out.root_y = s.y + map->desktop_offsets[i][1];
        return out;
    }
    return std::nullopt;
}

Resolved Service::resolve(const ScreenPoint& point, Purpose purpose) const {
    for (const auto& resolver : resolvers_)
        if (auto found = resolver->resolve(point, purpose)) return std::move(*found);
    return {};
}

Replies Service::handle_text(SessionState& state, std::string_view text, SteadyTime now) const {
    // Parsing checks the size before anything else.
    p::ParseLimits limits;
    limits.max_bytes = static_cast<std::size_t>(config_.limits.max_message_bytes);
    return handle(state, p::parse_message(text, limits), now);
}

Replies Service::handle_binary(SessionState& state) const {
    Replies out;
    out.replies.push_back(p::Error{std::nullopt, p::ErrorCode::bad_request, "binary frames are not accepted"});
    out.close = !state.welcomed;
    return out;
}

Replies Service::hello(SessionState& state, const p::Hello& hello, SteadyTime now) const {
    Replies out;
    out.close = true;
    bool flood_begins = false;
    {
        std::lock_guard lock(wrong_mutex_);
        auto it = wrong_tokens_.find(state.peer);
        if (it != wrong_tokens_.end() && now - it->second.since >= kWrongTokenWindow) {
            wrong_tokens_.erase(it);
            it = wrong_tokens_.end();
        }
        if (it != wrong_tokens_.end() && it->second.count >= kMaxWrongTokens) {
            out.replies.push_back(p::Error{hello.id, p::ErrorCode::rate_limited,
                                           "too many wrong pairing tokens from this address; wait a minute"});
            // The console hears of the first refusal only, not of a flood.
            flood_begins = it->second.count++ == kMaxWrongTokens;
        }
    }
    if (!out.replies.empty()) {
        if (activity_ && flood_begins) activity_->refused({hello.client, hello.device.value_or(""), state.peer, true});
        return out;
    }
    if (!config_.public_mode && !token_matches(hello.token)) {
        {
            std::lock_guard lock(wrong_mutex_);
            if (wrong_tokens_.size() > 4096) wrong_tokens_.clear();  // bounded, whatever the addresses
            auto& wrong = wrong_tokens_[state.peer];
            if (wrong.count == 0) wrong.since = now;
            ++wrong.count;
        }
        out.replies.push_back(p::Error{hello.id, p::ErrorCode::unauthorized, "unknown pairing token"});
        if (activity_) activity_->refused({hello.client, hello.device.value_or(""), state.peer, false});
        return out;
    }
    state.welcomed = true;
    state.id = next_session_++;
    state.token = config_.public_mode ? std::string() : hello.token;
    state.aims = aim_bucket(config_.limits);
    state.grabs = grab_bucket(config_.limits);
    out.close = false;
    const std::shared_ptr<const ScreenMap> map = screens();
    state.screens_generation = map->generation;
    state.client = hello.client;
    state.device = hello.device.value_or("");
    if (state.outbox)
        puts_->attach(state.id, [outbox = state.outbox, id = state.id](std::string message) {
            outbox(id, std::move(message));
        });
    if (activity_) activity_->welcomed({state.id, hello.client, state.peer});
    p::Welcome welcome{hello.id, config_.provider, map->field, config_.overlay, config_.limits};
    if (puts_->enabled()) {
        welcome.features.push_back(p::kFeaturePut);
        welcome.features.push_back(p::kFeaturePutHashAfter);
    }
    out.replies.push_back(std::move(welcome));
    return out;
}

std::optional<p::Message> Service::aim(SessionState& state, const p::Aim& aim, SteadyTime now) const {
    if (!state.aims.take(now)) {
        // The excess is dropped, with at most one error a second to say so.
        if (state.last_rate_error && now - *state.last_rate_error < std::chrono::seconds(1)) return std::nullopt;
        state.last_rate_error = now;
        char text[96];
        std::snprintf(text, sizeof text, "more than %g aims a second", config_.limits.aims_per_s);
        return p::Error{aim.id, p::ErrorCode::rate_limited, text};
    }
    p::Target target{aim.id, aim.point, p::ContentKind::none, ""};
    const auto point = screen_point(aim.point);
    if (point) {
        try {
            const Resolved found = resolve(*point, Purpose::preview);
            target.kind = found.kind;
            target.title = found.title;
        } catch (const std::exception&) {
            // A preview that fails says nothing; the grab reports the failure.
        }
    }
    if (activity_) activity_->aimed({state.id, aim.point, point, aim.confidence, target.kind, target.title});
    return target;
}

std::optional<p::Message> Service::grab(SessionState& state, const p::Grab& grab, SteadyTime now) const {
    if (!state.grabs.take(now)) {
        char text[96];
        std::snprintf(text, sizeof text, "more than %g grabs a minute", config_.limits.grabs_per_min);
        return p::Error{grab.id, p::ErrorCode::rate_limited, text};
    }
    const auto point = screen_point(grab.point);
    if (!point) return p::Error{grab.id, p::ErrorCode::not_found, "no screen shows field point " + point_text(grab.point)};
    Resolved resolved;
    try {
        resolved = resolve(*point, Purpose::grab);
    } catch (const std::exception& e) {
        return p::Error{grab.id, p::ErrorCode::internal, e.what()};
    }
    const bool file = resolved.file && resolved.kind != p::ContentKind::none && resolved.kind != p::ContentKind::url;
    if (!file)
        return answer_grab(state.id, state.token, grab, resolved, nullptr, *downloads_, config_.max_download_bytes,
                           activity_.get());
    std::optional<FileFacts> facts;
    try {
        if (!state.outbox) {
            facts = facts_->facts(*resolved.file);
        } else {
            // A large file is answered once hashed, from the hashing thread:
            // nothing of this Service but what the answer needs is held.
            facts = facts_->facts_or_later(
                *resolved.file, [outbox = state.outbox, session = state.id, token = state.token, grab, resolved,
                                 downloads = downloads_,
                                 limit = config_.max_download_bytes,
                                 activity = activity_](const std::variant<FileFacts, std::string>& result) {
                    const auto* known = std::get_if<FileFacts>(&result);
                    const p::Message reply = known ? answer_grab(session, token, grab, resolved, known, *downloads,
                                                                 limit, activity.get())
                                                   : unreadable(grab, resolved);
                    outbox(session, p::try_encode(reply).value_or(p::encode(p::Error{
                                        grab.id, p::ErrorCode::internal, "cannot encode the reply"})));
                });
        }
    } catch (const std::exception&) {
        return unreadable(grab, resolved);
    }
    if (!facts) return std::nullopt;
    return answer_grab(state.id, state.token, grab, resolved, &*facts, *downloads_, config_.max_download_bytes,
                       activity_.get());
}

p::Message Service::put(SessionState& state, const p::Put& put, SteadyTime now) const {
    if (!puts_->enabled()) return p::Error{put.id, p::ErrorCode::refused, "this provider takes no puts"};
    if (!state.grabs.take(now)) {
        char text[96];
        std::snprintf(text, sizeof text, "more than %g grabs and puts a minute", config_.limits.grabs_per_min);
        return p::Error{put.id, p::ErrorCode::rate_limited, text};
    }
    const auto point = screen_point(put.point);
    if (!point) return p::Error{put.id, p::ErrorCode::not_found, "no screen shows field point " + point_text(put.point)};
    return puts_->offer({state.id, state.client, state.device}, put, point);
}

Replies Service::handle(SessionState& state, const p::ParseResult& parsed, SteadyTime now) const {
    Replies out;
    if (const auto* error = std::get_if<p::ProtocolError>(&parsed)) {
        out.replies.push_back(p::to_error(*error));
        out.close = !state.welcomed;
        return out;
    }
    const p::Message& message = std::get<p::Message>(parsed);

    if (!state.welcomed) {
        if (const auto* h = std::get_if<p::Hello>(&message)) return hello(state, *h, now);
        out.replies.push_back(p::Error{std::nullopt, p::ErrorCode::unauthorized,
                                       std::string("a session starts with hello, not ") + p::type_name(message)});
        out.close = true;
        return out;
    }
    if (state.screens_generation != screens()->generation) {
        out.close = true;
        out.restart = true;
        return out;
    }

    std::visit(
        [&](const auto& m) {
            using T = std::decay_t<decltype(m)>;
            if constexpr (std::is_same_v<T, p::Seeking>) {
                // No reply. Counted with the aims (the excess is not
                // reported); the overlay's on-demand activation listens.
                if (state.aims.take(now) && activity_) activity_->seeking(state.id);
            } else if constexpr (std::is_same_v<T, p::Aim>) {
                if (auto reply = aim(state, m, now)) out.replies.push_back(std::move(*reply));
            } else if constexpr (std::is_same_v<T, p::Grab>) {
                if (auto reply = grab(state, m, now)) out.replies.push_back(std::move(*reply));
            } else if constexpr (std::is_same_v<T, p::Put>) {
                out.replies.push_back(put(state, m, now));
            } else if constexpr (std::is_same_v<T, p::Hello>) {
                out.replies.push_back(p::Error{m.id, p::ErrorCode::bad_request, "this session is already welcomed"});
            } else {
                out.replies.push_back(p::Error{std::nullopt, p::ErrorCode::bad_request,
                                               std::string("\"") + p::type_name(message) +
                                                   "\" is a provider's message, not a request"});
            }
        },
        message);
    return out;
}

}  // namespace umf::provider
