#include "shared/protocol/messages.hpp"

#include <cctype>
#include <cmath>
#include <iterator>
#include <limits>
#include <nlohmann/json.hpp>
#include <stdexcept>

#include "shared/field/field_io.hpp"
#include "shared/protocol/json_checks.hpp"

namespace umf::protocol {

namespace {

using nlohmann::json;
using nlohmann::ordered_json;

// ---- reading --------------------------------------------------------------

struct IdRead {
    std::optional<RequestId> id;
    std::string problem;
};

IdRead read_id(const json& doc) {
    auto it = doc.find("id");
    if (it == doc.end() || it->is_null()) return {};
    if (it->is_string()) {
        const auto& s = it->get_ref<const std::string&>();
        if (s.empty() || s.size() > kMaxIdBytes)
            return {std::nullopt, "\"id\" must be 1 to " + std::to_string(kMaxIdBytes) + " bytes long, not " +
                                      std::to_string(s.size())};
        return {RequestId{s}, {}};
    }
    if (auto n = integer_in(*it, -kMaxSafeInteger, kMaxSafeInteger)) return {RequestId{*n}, {}};
    return {std::nullopt, "\"id\" must be a string or an integer within +-(2^53 - 1)"};
}

std::optional<FieldPoint> point_from(const json& v) {
    if (!v.is_array() || v.size() != 2) return std::nullopt;
    auto u = finite_number(v[0]);
    auto w = finite_number(v[1]);
    if (!u || !w || std::abs(*u) > kMaxCoordinate || std::abs(*w) > kMaxCoordinate) return std::nullopt;
    return FieldPoint{*u, *w};
}

const char* const kPointShape = " must be [u, v]: two numbers within +-1e6";

FieldPoint read_point(MemberReader& r, const char* key) {
    const json* v = r.get(key);
    if (!r.ok()) return {};
    if (!v) {
        r.fail("missing " + r.name(key));
        return {};
    }
    auto p = point_from(*v);
    if (!p) r.fail(r.name(key) + kPointShape);
    return p.value_or(FieldPoint{});
}

ContentKind read_kind(MemberReader& r) {
    std::string name = r.text("kind", 1, 16);
    if (!r.ok()) return ContentKind::none;
    auto kind = content_kind_from_string(name);
    if (!kind) r.fail("\"kind\" must be \"url\", \"file\", \"snapshot\" or \"none\"");
    return kind.value_or(ContentKind::none);
}


bool is_file_name(std::string_view name) {
    if (name.empty() || name == "." || name == "..") return false;
    if (has_control_chars(name)) return false;
    return name.find_first_of("/\\") == std::string_view::npos;
}

// A path on the provider, appended to https://HOST:PORT. Only unreserved
// characters and '/', and never "//" at the start (a scheme-relative URL
// would leave the host): it cannot point anywhere but the provider.
bool is_download_path(std::string_view path) {
    if (path.size() < 2 || path[0] != '/' || path[1] == '/') return false;
    for (char c : path) {
        bool ok = (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || (c >= '0' && c <= '9') || c == '-' ||
                  c == '_' || c == '.' || c == '~' || c == '/';
        if (!ok) return false;
    }
    return true;
}

bool is_printable_ascii(std::string_view s) {
    for (char c : s)
        if (c < 0x20 || c > 0x7e) return false;
    return true;
}

Hello read_hello(MemberReader& r) {
    Hello m;
    m.token = r.text("token", 1, kMaxTokenBytes);
    m.client = r.text("client", 0, kMaxNameBytes);
    m.device = r.optional_text("device", 1, kMaxDeviceBytes);
    if (r.ok() && m.device && !is_printable_ascii(*m.device))
        r.fail("\"device\" must be printable ASCII, 1 to " + std::to_string(kMaxDeviceBytes) + " bytes");
    return m;
}

FieldInfo read_field_info(const json& field_json, MemberReader& outer) {
    FieldInfo info;
    MemberReader r(field_json, "field");
    const json* def = r.object("definition");
    if (def && r.ok()) {
        // field_io is the one parser of field definitions; its messages name the defect.
        try {
            info.definition = parse_field(def->dump(), "\"field.definition\"");
        } catch (const std::exception& e) {
            r.fail(e.what());
        }
    }
    const json* screens = r.array("screens", 1, kMaxScreens);
    if (screens && r.ok()) {
        for (std::size_t i = 0; i < screens->size() && r.ok(); ++i) {
            MemberReader s((*screens)[i], "field.screens[" + std::to_string(i) + "]");
            Screen screen;
            screen.name = s.text("name", 0, kMaxNameBytes);
            if (const json* region = s.array("region", 4, 4); region && s.ok()) {
                auto coordinate = [&](std::size_t k) { return finite_number((*region)[k]); };
                auto u0 = coordinate(0), v0 = coordinate(1), u1 = coordinate(2), v1 = coordinate(3);
                if (!u0 || !v0 || !u1 || !v1 || !(*u0 >= 0 && *u0 < *u1 && *u1 <= info.definition.width) ||
                    !(*v0 >= 0 && *v0 < *v1 && *v1 <= info.definition.height))
                    s.fail(s.name("region") + " must be [u0, v0, u1, v1] with 0 <= u0 < u1 <= " +
                           std::to_string(info.definition.width) + " and 0 <= v0 < v1 <= " +
                           std::to_string(info.definition.height));
                else
                    screen.region = FieldRect{*u0, *v0, *u1, *v1};
            }
            if (const json* pixels = s.array("pixels", 2, 2); pixels && s.ok()) {
                auto w = integer_in((*pixels)[0], 1, 65536), h = integer_in((*pixels)[1], 1, 65536);
                if (!w || !h) {
                    s.fail(s.name("pixels") + " must be [width, height], integers 1..65536");
                } else {
                    screen.width_px = static_cast<int>(*w);
                    screen.height_px = static_cast<int>(*h);
                }
            }
            if (!s.ok()) r.fail(s.problem());
            for (std::size_t j = 0; j < info.screens.size() && r.ok(); ++j) {
                const auto& a = info.screens[j].region;
                const auto& b = screen.region;
                if (a.u0 < b.u1 && b.u0 < a.u1 && a.v0 < b.v1 && b.v0 < a.v1)
                    r.fail("\"field.screens\": the regions of screens " + std::to_string(j) + " and " +
                           std::to_string(i) + " overlap");
            }
            info.screens.push_back(std::move(screen));
        }
    }
    if (!r.ok()) outer.fail(r.problem());
    return info;
}

Welcome read_welcome(MemberReader& r) {
    Welcome m;
    if (const json* provider = r.object("provider")) {
        MemberReader p(*provider, "provider");
        m.provider.name = p.text("name", 1, kMaxNameBytes);
        m.provider.software = p.text("software", 0, kMaxNameBytes);
        if (!p.ok()) r.fail(p.problem());
    }
    if (const json* field = r.object("field")) m.field = read_field_info(*field, r);
    if (const json* overlay = r.object("overlay")) {
        MemberReader o(*overlay, "overlay");
        m.overlay.preset = o.text("preset", 1, kMaxOverlayNameBytes);
        m.overlay.opacity_min = o.number("opacity_min", 0.0, 1.0);
        m.overlay.opacity_max = o.number("opacity_max", 0.0, 1.0);
        m.overlay.period_s = o.number("period_s", 0.0, kMaxPulsePeriodS);
        std::string waveform = o.text("waveform", 1, 16);
        if (o.ok() && m.overlay.opacity_min > m.overlay.opacity_max)
            o.fail("\"overlay.opacity_min\" is above \"overlay.opacity_max\"");
        if (o.ok() && m.overlay.period_s != 0.0 && m.overlay.period_s < kMinPulsePeriodS)
            o.fail("\"overlay.period_s\" must be 0 or at least 0.5");
        if (o.ok()) {
            auto w = pulse_waveform_from_string(waveform);
            if (!w) o.fail("\"overlay.waveform\" must be \"sine\" or \"triangle\"");
            m.overlay.waveform = w.value_or(PulseWaveform::sine);
        }
        if (!o.ok()) r.fail(o.problem());
    }
    if (const json* limits = r.object("limits")) {
        MemberReader l(*limits, "limits");
        m.limits.max_message_bytes = l.integer("max_message_bytes", 1024, 16 << 20);
        m.limits.aims_per_s = l.number("aims_per_s", 0.1, 100.0);
        m.limits.grabs_per_min = l.number("grabs_per_min", 0.1, 1000.0);
        m.limits.download_ttl_s = l.number("download_ttl_s", 1.0, 3600.0);
        if (!l.ok()) r.fail(l.problem());
    }
    if (r.ok() && r.has("features")) {
        if (const json* features = r.array("features", 0, kMaxFeatures); features && r.ok()) {
            for (const json& f : *features) {
                if (!f.is_string() || f.get_ref<const std::string&>().empty() ||
                    f.get_ref<const std::string&>().size() > kMaxFeatureBytes) {
                    r.fail("\"features\" must be an array of at most " + std::to_string(kMaxFeatures) +
                           " strings of 1 to " + std::to_string(kMaxFeatureBytes) + " bytes");
                    break;
                }
                m.features.push_back(f.get<std::string>());
            }
        }
    }
    return m;
}

Aim read_aim(MemberReader& r) {
    Aim m;
    m.point = read_point(r, "point");
    m.confidence = r.number("confidence", 0.0, 1.0);
    return m;
}

Target read_target(MemberReader& r) {
    Target m;
    m.point = read_point(r, "point");
    m.kind = read_kind(r);
    m.title = r.text("title", 0, kMaxTitleBytes);
    return m;
}

Grab read_grab(MemberReader& r) {
    Grab m;
    m.point = read_point(r, "point");
    return m;
}

std::optional<std::string> read_url(MemberReader& r) {
    auto url = r.optional_text("url", 1, kMaxUrlBytes);
    if (r.ok() && url && !is_http_url(*url))
        r.fail("\"url\" must be an http: or https: URL without spaces or control characters");
    return url;
}

std::optional<std::string> read_file_name(MemberReader& r) {
    auto name = r.optional_text("name", 1, kMaxFileNameBytes);
    if (r.ok() && name && !is_file_name(*name))
        r.fail("\"name\" must be a file name: no '/', '\\' or control characters, not \".\" or \"..\"");
    return name;
}

// name, mime, size and sha256 of a content or a put, each optional here.
template <class M>
void read_file_members(MemberReader& r, M& m) {
    m.name = read_file_name(r);
    m.mime = r.optional_text("mime", 3, kMaxMimeBytes);
    if (r.ok() && m.mime && !is_mime_type(*m.mime)) r.fail("\"mime\" must be a media type such as \"text/plain\"");
    m.size = r.optional_integer("size", 0, kMaxSafeInteger);
    m.sha256 = r.optional_text("sha256", 64, 64);
    if (r.ok() && m.sha256 && !is_lower_hex(*m.sha256)) r.fail("\"sha256\" must be 64 lowercase hex digits");
}

std::optional<std::string> read_path(MemberReader& r, const char* key) {
    auto path = r.optional_text(key, 2, kMaxDownloadPathBytes);
    if (r.ok() && path && !is_download_path(*path))
        r.fail(r.name(key) +
               " must be a path such as \"/dl/abc\": '/' then letters, digits, '-', '_', '.', '~', '/'");
    return path;
}

Content read_content(MemberReader& r) {
    Content m;
    m.kind = read_kind(r);
    m.title = r.text("title", 0, kMaxTitleBytes);
    m.url = read_url(r);
    read_file_members(r, m);
    m.download = read_path(r, "download");
    if (!r.ok()) return m;
    auto need = [&](bool present, const char* member) {
        if (!present && r.ok()) r.fail(std::string("a ") + to_string(m.kind) + " content needs \"" + member + "\"");
    };
    if (m.kind == ContentKind::url) need(m.url.has_value(), "url");
    if (m.kind == ContentKind::file || m.kind == ContentKind::snapshot) {
        need(m.name.has_value(), "name");
        need(m.mime.has_value(), "mime");
        need(m.size.has_value(), "size");
        need(m.download.has_value(), "download");
    }
    return m;
}

Put read_put(MemberReader& r) {
    Put m;
    m.point = read_point(r, "point");
    m.kind = read_kind(r);
    if (r.ok() && m.kind != ContentKind::url && m.kind != ContentKind::file)
        r.fail("\"kind\" of a put must be \"url\" or \"file\"");
    m.title = r.optional_text("title", 0, kMaxTitleBytes).value_or("");
    m.url = read_url(r);
    read_file_members(r, m);
    if (!r.ok()) return m;
    auto need = [&](bool present, const char* member) {
        if (!present && r.ok()) r.fail(std::string("a ") + to_string(m.kind) + " put needs \"" + member + "\"");
    };
    if (m.kind == ContentKind::url) need(m.url.has_value(), "url");
    if (m.kind == ContentKind::file) {
        need(m.name.has_value(), "name");
        need(m.mime.has_value(), "mime");
        need(m.size.has_value(), "size");
    }
    return m;
}

PutStatus read_put_status(MemberReader& r) {
    PutStatus m;
    const std::string status = r.text("status", 1, 16);
    if (r.ok()) {
        if (status == "asking")
            m.status = PutState::asking;
        else if (status == "upload")
            m.status = PutState::upload;
        else if (status == "done")
            m.status = PutState::done;
        else
            r.fail("\"status\" must be \"asking\", \"upload\" or \"done\"");
    }
    m.upload = read_path(r, "upload");
    const auto outcome = r.optional_text("outcome", 1, 16);
    if (r.ok() && outcome) {
        if (*outcome == "saved")
            m.outcome = PutOutcome::saved;
        else if (*outcome == "opened")
            m.outcome = PutOutcome::opened;
        else
            r.fail("\"outcome\" must be \"saved\" or \"opened\"");
    }
    m.name = read_file_name(r);
    if (!r.ok()) return m;
    if (m.status == PutState::upload && !m.upload) r.fail("an upload put_status needs \"upload\"");
    if (m.status == PutState::done && !m.outcome) r.fail("a done put_status needs \"outcome\"");
    if (r.ok() && m.outcome == PutOutcome::saved && !m.name) r.fail("a saved put_status needs \"name\"");
    return m;
}

Error read_error(MemberReader& r) {
    Error m;
    std::string code = r.text("code", 1, 32);
    if (r.ok()) {
        auto c = error_code_from_string(code);
        if (!c) r.fail("\"code\" is not an error code of version 1");
        m.code = c.value_or(ErrorCode::internal);
    }
    m.message = r.text("message", 0, kMaxErrorMessageBytes);
    return m;
}

// The message of a JSON object whose "type" is `type`; the id is set by the caller.
std::optional<Message> read_body(const std::string& type, MemberReader& r) {
    if (type == "hello") return read_hello(r);
    if (type == "welcome") return read_welcome(r);
    if (type == "seeking") return Seeking{};
    if (type == "aim") return read_aim(r);
    if (type == "target") return read_target(r);
    if (type == "grab") return read_grab(r);
    if (type == "content") return read_content(r);
    if (type == "error") return read_error(r);
    if (type == "put") return read_put(r);
    if (type == "put_status") return read_put_status(r);
    return std::nullopt;
}

// Every message type but Seeking has an id; Grab, Content, Put and PutStatus must.
struct SetId {
    std::optional<RequestId> id;
    void operator()(Seeking&) const {}
    void operator()(Grab& m) const { m.id = *id; }
    void operator()(Content& m) const { m.id = *id; }
    void operator()(Put& m) const { m.id = *id; }
    void operator()(PutStatus& m) const { m.id = *id; }
    template <class M>
    void operator()(M& m) const {
        m.id = id;
    }
};

ProtocolError problem(ErrorCode code, std::string message, std::optional<RequestId> id = std::nullopt) {
    return ProtocolError{code, std::move(message), std::move(id)};
}

ParseResult parse_document(std::string_view text, const ParseLimits& limits) {
    if (text.size() > limits.max_bytes)
        return problem(ErrorCode::too_large, "message is " + std::to_string(text.size()) +
                                                 " bytes, more than the limit of " + std::to_string(limits.max_bytes));
    // nlohmann's parser keeps its own stack, so depth cannot overflow ours,
    // but a message has no use for deep nesting: containers below the limit
    // are discarded as they are read and the message refused.
    bool too_deep = false;
    const int max_depth = limits.max_depth;
    json::parser_callback_t watch_depth = [&too_deep, max_depth](int depth, json::parse_event_t event, json&) {
        // `depth` counts the containers around this one.
        if ((event == json::parse_event_t::object_start || event == json::parse_event_t::array_start) &&
            depth + 1 > max_depth) {
            too_deep = true;
            return false;
        }
        return true;
    };
    json doc = json::parse(text.begin(), text.end(), watch_depth, /*allow_exceptions=*/false);
    if (too_deep) return problem(ErrorCode::bad_request, "nested deeper than " + std::to_string(max_depth) + " levels");
    if (doc.is_discarded())
        return problem(ErrorCode::bad_request, is_valid_utf8(text) ? "not valid JSON" : "not valid UTF-8");
    if (!doc.is_object()) return problem(ErrorCode::bad_request, "the message must be a JSON object");

    // The id first, so that every later problem can be answered to it.
    IdRead id = read_id(doc);
    if (!id.problem.empty()) return problem(ErrorCode::bad_request, id.problem);

    MemberReader r(doc);
    std::string type = r.text("type", 1, 32);
    if (!r.ok()) return problem(ErrorCode::bad_request, r.problem(), id.id);
    if (!r.has("v")) return problem(ErrorCode::bad_request, "missing \"v\" (the protocol version, 1)", id.id);
    auto version = integer_in(*r.get("v"), std::numeric_limits<std::int64_t>::min(),
                              std::numeric_limits<std::int64_t>::max());
    if (!version) return problem(ErrorCode::bad_request, "\"v\" must be an integer, the protocol version", id.id);
    if (*version != kProtocolVersion)
        return problem(ErrorCode::unsupported_version, "version " + std::to_string(*version) +
                                                           " is not supported; this side speaks version " +
                                                           std::to_string(kProtocolVersion),
                       id.id);

    auto message = read_body(type, r);
    if (!message) return problem(ErrorCode::bad_request, "unknown type \"" + clip_text(type, 32) + "\"", id.id);
    if (!r.ok()) return problem(ErrorCode::bad_request, r.problem(), id.id);
    if ((type == "grab" || type == "content" || type == "put" || type == "put_status") && !id.id)
        return problem(ErrorCode::bad_request, "a " + type + " needs an \"id\"");
    std::visit(SetId{id.id}, *message);
    return *message;
}

// ---- writing --------------------------------------------------------------

void put_id(ordered_json& o, const std::optional<RequestId>& id) {
    if (!id) return;
    if (const auto* n = std::get_if<std::int64_t>(&*id))
        o["id"] = *n;
    else
        o["id"] = std::get<std::string>(*id);
}

ordered_json header(const char* type, const std::optional<RequestId>& id) {
    ordered_json o;
    o["type"] = type;
    o["v"] = kProtocolVersion;
    put_id(o, id);
    return o;
}

ordered_json point_json(const FieldPoint& p) { return ordered_json::array({p.u, p.v}); }

// Writes a message as JSON. The one problem it can find itself (an invalid
// field, which field_to_json would throw on) goes to `problem`; the parser
// checks the rest.
struct Writer {
    std::string* problem;

    ordered_json operator()(const Hello& m) const {
        auto o = header("hello", m.id);
        o["token"] = m.token;
        o["client"] = clip_text(m.client, kMaxNameBytes);
        if (m.device) o["device"] = *m.device;
        return o;
    }
    ordered_json operator()(const Welcome& m) const {
        auto o = header("welcome", m.id);
        o["provider"] = {{"name", clip_text(m.provider.name, kMaxNameBytes)},
                         {"software", clip_text(m.provider.software, kMaxNameBytes)}};
        if (auto defect = describe_invalid(m.field.definition); !defect.empty()) {
            *problem = "\"field.definition\": " + defect;
            return o;
        }
        ordered_json field;
        field["definition"] = ordered_json::parse(field_to_json(m.field.definition));
        ordered_json screens = ordered_json::array();
        for (const auto& s : m.field.screens) {
            ordered_json screen;
            screen["name"] = clip_text(s.name, kMaxNameBytes);
            screen["region"] = {s.region.u0, s.region.v0, s.region.u1, s.region.v1};
            screen["pixels"] = {s.width_px, s.height_px};
            screens.push_back(std::move(screen));
        }
        field["screens"] = std::move(screens);
        o["field"] = std::move(field);
        ordered_json overlay;
        overlay["preset"] = clip_text(m.overlay.preset, kMaxOverlayNameBytes);
        overlay["opacity_min"] = m.overlay.opacity_min;
        overlay["opacity_max"] = m.overlay.opacity_max;
        overlay["period_s"] = m.overlay.period_s;
        overlay["waveform"] = to_string(m.overlay.waveform);
        o["overlay"] = std::move(overlay);
        ordered_json limits;
        limits["max_message_bytes"] = m.limits.max_message_bytes;
        limits["aims_per_s"] = m.limits.aims_per_s;
        limits["grabs_per_min"] = m.limits.grabs_per_min;
        limits["download_ttl_s"] = m.limits.download_ttl_s;
        o["limits"] = std::move(limits);
        if (!m.features.empty()) o["features"] = m.features;
        return o;
    }
    ordered_json operator()(const Seeking&) const { return header("seeking", std::nullopt); }
    ordered_json operator()(const Aim& m) const {
        auto o = header("aim", m.id);
        o["point"] = point_json(m.point);
        o["confidence"] = m.confidence;
        return o;
    }
    ordered_json operator()(const Target& m) const {
        auto o = header("target", m.id);
        o["point"] = point_json(m.point);
        o["kind"] = to_string(m.kind);
        o["title"] = clip_text(m.title, kMaxTitleBytes);
        return o;
    }
    ordered_json operator()(const Grab& m) const {
        auto o = header("grab", m.id);
        o["point"] = point_json(m.point);
        return o;
    }
    ordered_json operator()(const Content& m) const {
        auto o = header("content", m.id);
        o["kind"] = to_string(m.kind);
        o["title"] = clip_text(m.title, kMaxTitleBytes);
        if (m.url) o["url"] = *m.url;
        if (m.name) o["name"] = *m.name;
        if (m.mime) o["mime"] = *m.mime;
        if (m.size) o["size"] = *m.size;
        if (m.sha256) o["sha256"] = *m.sha256;
        if (m.download) o["download"] = *m.download;
        return o;
    }
    ordered_json operator()(const Put& m) const {
        auto o = header("put", m.id);
        o["point"] = point_json(m.point);
        o["kind"] = to_string(m.kind);
        if (!m.title.empty()) o["title"] = clip_text(m.title, kMaxTitleBytes);
        if (m.url) o["url"] = *m.url;
        if (m.name) o["name"] = *m.name;
        if (m.mime) o["mime"] = *m.mime;
        if (m.size) o["size"] = *m.size;
        if (m.sha256) o["sha256"] = *m.sha256;
        return o;
    }
    ordered_json operator()(const PutStatus& m) const {
        auto o = header("put_status", m.id);
        o["status"] = to_string(m.status);
        if (m.upload) o["upload"] = *m.upload;
        if (m.outcome) o["outcome"] = to_string(*m.outcome);
        if (m.name) o["name"] = *m.name;
        return o;
    }
    ordered_json operator()(const Error& m) const {
        auto o = header("error", m.id);
        o["code"] = to_string(m.code);
        o["message"] = clip_text(m.message, kMaxErrorMessageBytes);
        return o;
    }
};

}  // namespace

bool FieldInfo::operator==(const FieldInfo& o) const {
    const Field& a = definition;
    const Field& b = o.definition;
    return a.id == b.id && a.width == b.width && a.height == b.height && a.window == b.window &&
           a.colors == b.colors && a.key == b.key && a.palette == b.palette && a.modules == b.modules &&
           screens == o.screens;
}

const char* to_string(ContentKind kind) {
    switch (kind) {
        case ContentKind::url: return "url";
        case ContentKind::file: return "file";
        case ContentKind::snapshot: return "snapshot";
        case ContentKind::none: return "none";
    }
    return "none";
}

std::optional<ContentKind> content_kind_from_string(std::string_view name) {
    for (ContentKind k : {ContentKind::url, ContentKind::file, ContentKind::snapshot, ContentKind::none})
        if (name == to_string(k)) return k;
    return std::nullopt;
}

const char* to_string(PutState state) {
    switch (state) {
        case PutState::asking: return "asking";
        case PutState::upload: return "upload";
        case PutState::done: return "done";
    }
    return "asking";
}

const char* to_string(PutOutcome outcome) {
    switch (outcome) {
        case PutOutcome::saved: return "saved";
        case PutOutcome::opened: return "opened";
    }
    return "saved";
}

const char* to_string(PulseWaveform waveform) { return waveform == PulseWaveform::triangle ? "triangle" : "sine"; }

std::optional<PulseWaveform> pulse_waveform_from_string(std::string_view name) {
    if (name == "sine") return PulseWaveform::sine;
    if (name == "triangle") return PulseWaveform::triangle;
    return std::nullopt;
}

const char* type_name(const Message& message) {
    static constexpr const char* kNames[] = {"hello", "welcome", "seeking", "aim", "target",
                                             "grab",  "content", "error",   "put", "put_status"};
    static_assert(std::size(kNames) == std::variant_size_v<Message>);
    return kNames[message.index()];
}

bool is_request(const Message& message) {
    return std::holds_alternative<Hello>(message) || std::holds_alternative<Seeking>(message) ||
           std::holds_alternative<Aim>(message) || std::holds_alternative<Grab>(message) ||
           std::holds_alternative<Put>(message);
}

std::optional<std::string> try_encode(const Message& message, std::string* problem) {
    std::string defect;
    ordered_json o = std::visit(Writer{&defect}, message);
    if (defect.empty()) {
        // Invalid UTF-8 left in an identifier is replaced rather than thrown
        // on here; the check below then refuses it where it matters.
        std::string text = o.dump(-1, ' ', false, ordered_json::error_handler_t::replace);
        // The parser is the one definition of a valid message: what it
        // refuses is not sent.
        ParseResult back = parse_message(text, ParseLimits{std::numeric_limits<std::size_t>::max(), kMaxDepth});
        const auto* e = std::get_if<ProtocolError>(&back);
        if (!e) return text;
        defect = e->message;
    }
    if (problem) *problem = std::string("cannot encode the ") + type_name(message) + " message: " + defect;
    return std::nullopt;
}

std::string encode(const Message& message) {
    std::string problem;
    auto text = try_encode(message, &problem);
    if (!text) throw std::invalid_argument(problem);
    return std::move(*text);
}

ParseResult parse_message(std::string_view text, const ParseLimits& limits) {
    try {
        return parse_document(text, limits);
    } catch (const std::exception& e) {
        // Not expected (every access above is checked first); out of memory at worst.
        return problem(ErrorCode::bad_request, std::string("cannot read the message: ") + e.what());
    }
}

Error to_error(const ProtocolError& e) { return Error{e.id, e.code, clip_text(e.message, kMaxErrorMessageBytes)}; }

std::string safe_file_name(std::string_view name) {
    std::string out = clip_text(name, kMaxFileNameBytes);
    for (char& c : out)
        if (c == '/' || c == '\\' || static_cast<unsigned char>(c) < 0x20 || c == 0x7f) c = '_';
    if (out.empty() || out == "." || out == "..") return "file";
    return out;
}

bool is_http_url(std::string_view url) {
    auto starts = [&](std::string_view scheme) {
        if (url.size() <= scheme.size()) return false;
        for (std::size_t i = 0; i < scheme.size(); ++i)
            if (std::tolower(static_cast<unsigned char>(url[i])) != scheme[i]) return false;
        return true;
    };
    if (!starts("http://") && !starts("https://")) return false;
    for (char c : url)
        if (c == ' ' || static_cast<unsigned char>(c) < 0x20 || c == 0x7f) return false;
    return true;
}

bool is_mime_type(std::string_view mime) {
    if (mime.size() < 3 || mime.size() > kMaxMimeBytes) return false;
    for (char c : mime)
        if (c < 0x20 || c > 0x7e) return false;  // printable ASCII only (char may be signed: UTF-8 is < 0 there)
    auto slash = mime.find('/');
    return slash != std::string_view::npos && slash > 0 && slash + 1 < mime.size() && mime[slash + 1] != ' ';
}

}  // namespace umf::protocol
