// The messages between a requester and a provider, protocol version 1.
// docs/PROTOCOL.md is the specification; this is its one implementation.
//
// Every message is a JSON object with "type" and "v" (the version). Requests
// that expect a reply may carry an "id" (a string or an integer of the
// requester's choosing) that the reply echoes; a grab must carry one.
// Members this version does not know are ignored, so a later minor addition
// does not break an older peer; a JSON null counts as an absent member.
//
// Parsing never throws and never trusts its input: size, nesting depth,
// UTF-8, types, ranges and string lengths are checked, and the first problem
// comes back as a ProtocolError with the code to answer with and, when it
// could be read, the request's id.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <optional>
#include <string>
#include <string_view>
#include <variant>
#include <vector>

#include "shared/field/field.hpp"
#include "shared/protocol/error_codes.hpp"

namespace umf::protocol {

inline constexpr int kProtocolVersion = 1;

// Caps on received text, in bytes. Display text the provider sends (titles,
// names, error messages) is clipped to them by encode(); identifiers, tokens,
// URLs and file details are refused instead, since a shortened one is wrong.
inline constexpr std::size_t kMaxTokenBytes = 128;
inline constexpr std::size_t kMaxIdBytes = 64;
inline constexpr std::size_t kMaxTitleBytes = 512;
inline constexpr std::size_t kMaxNameBytes = 128;  // client, provider and screen names
inline constexpr std::size_t kMaxFileNameBytes = 255;
inline constexpr std::size_t kMaxUrlBytes = 8192;
inline constexpr std::size_t kMaxMimeBytes = 255;
inline constexpr std::size_t kMaxDownloadPathBytes = 256;
inline constexpr std::size_t kMaxErrorMessageBytes = 1024;
inline constexpr std::size_t kMaxScreens = 16;
inline constexpr std::size_t kMaxDeviceBytes = 64;   // a hello's device: printable ASCII
inline constexpr std::size_t kMaxFeatures = 32;      // a welcome's features, each 1..kMaxFeatureBytes
inline constexpr std::size_t kMaxFeatureBytes = 64;
// The feature a provider that takes puts names in its welcome.
inline constexpr const char* kFeaturePut = "put";
// A file put may leave out sha256 and name it after the bytes
// (docs/PROTOCOL.md, "The hash after the bytes").
inline constexpr const char* kFeaturePutHashAfter = "put-hash-after";
// |u| and |v| of any field point: far outside any field, yet small enough that
// the provider's arithmetic on them stays exact to a fraction of a pixel.
inline constexpr double kMaxCoordinate = 1e6;

// What a provider accepts by default (and announces in Limits), and what a
// requester accepts: a welcome carries the whole field, 8 KB for 120 x 68
// modules, about 1 byte a module beyond that.
inline constexpr std::size_t kMaxRequestBytes = 16 * 1024;
inline constexpr std::size_t kMaxReplyBytes = 1024 * 1024;
inline constexpr int kMaxDepth = 16;

struct ParseLimits {
    std::size_t max_bytes = kMaxRequestBytes;  // checked before any parsing
    int max_depth = kMaxDepth;                 // a top-level object is depth 1
};
// The provider parses with ParseLimits{}; a requester with these.
inline constexpr ParseLimits kRequesterLimits{kMaxReplyBytes, kMaxDepth};

// A string of 1..kMaxIdBytes bytes or an integer within +-(2^53 - 1).
using RequestId = std::variant<std::int64_t, std::string>;

// A point in field modules: origin at the field's top-left corner, u to the
// right, v down; (0.5, 0.5) is the centre of the top-left module.
struct FieldPoint {
    double u = 0.0;
    double v = 0.0;
    bool operator==(const FieldPoint&) const = default;
};

// What would be taken at a point: a link, a file, an image of the screen
// there, or nothing.
enum class ContentKind { url, file, snapshot, none };
const char* to_string(ContentKind kind);
std::optional<ContentKind> content_kind_from_string(std::string_view name);

// requester -> provider, first message of a session.
struct Hello {
    std::optional<RequestId> id;
    std::string token;   // the pairing token, 1..kMaxTokenBytes
    std::string client;  // display text: "umf-web/0.1 (Android; Chrome 120)"
    // A name the requester keeps, 1..kMaxDeviceBytes of printable ASCII, so
    // the screen can accept its puts without asking each time.
    std::optional<std::string> device{};
    bool operator==(const Hello&) const = default;
};

struct ProviderInfo {
    std::string name;      // display text, e.g. the host name; not empty
    std::string software;  // display text: "umf-provider/0.1.0"
    bool operator==(const ProviderInfo&) const = default;
};

// A rectangle of the field in modules: u0 < u1, v0 < v1, within the field.
struct FieldRect {
    double u0 = 0.0, v0 = 0.0, u1 = 0.0, v1 = 0.0;
    bool operator==(const FieldRect&) const = default;
};

// One screen and the part of the field it shows. Regions of different screens
// do not overlap, so a field point names at most one screen.
struct Screen {
    std::string name;  // display text: "DP-1", "Dell U2720Q"
    FieldRect region;
    int width_px = 0;  // the screen's size, 1..65536 each
    int height_px = 0;
    bool operator==(const Screen&) const = default;
};

// Everything a requester needs to detect the field and to say where it aims.
struct FieldInfo {
    Field definition;  // as in a umf-field/1 file
    std::vector<Screen> screens;  // 1..kMaxScreens
    bool operator==(const FieldInfo& other) const;
};

// How the field is mixed, so a requester can expect its contrast: the wire's
// own description of the provider's preset (the provider fills it in from
// its overlay settings; the protocol knows nothing of them).
enum class PulseWaveform { sine, triangle };
const char* to_string(PulseWaveform waveform);
std::optional<PulseWaveform> pulse_waveform_from_string(std::string_view name);

inline constexpr std::size_t kMaxOverlayNameBytes = 64;
inline constexpr double kMinPulsePeriodS = 0.5;  // a period is 0 (static) or at least this
inline constexpr double kMaxPulsePeriodS = 60.0;

struct OverlayInfo {
    std::string preset;
    double opacity_min = 0.0;
    double opacity_max = 0.0;
    double period_s = 0.0;  // 0: static
    PulseWaveform waveform = PulseWaveform::sine;
    bool operator==(const OverlayInfo&) const = default;
};

// What the provider accepts. seeking and aim messages share aims_per_s.
struct Limits {
    std::int64_t max_message_bytes = kMaxRequestBytes;  // 1024..16 MiB
    double aims_per_s = 10.0;                           // 0.1..100
    double grabs_per_min = 30.0;                        // 0.1..1000
    double download_ttl_s = 60.0;                       // 1..3600
    bool operator==(const Limits&) const = default;
};

// provider -> requester, the answer to a good hello.
struct Welcome {
    std::optional<RequestId> id;  // the hello's
    ProviderInfo provider;
    FieldInfo field;
    OverlayInfo overlay;
    Limits limits;
    // What the provider offers beyond version 1's core: "put". Left out of the
    // text when empty; unknown names are kept (a requester ignores them).
    std::vector<std::string> features{};
    bool operator==(const Welcome&) const = default;
};

// requester -> provider: the camera is on but has no lock. No reply.
struct Seeking {
    bool operator==(const Seeking&) const = default;
};

// requester -> provider, a few times a second while locked.
struct Aim {
    std::optional<RequestId> id;
    FieldPoint point;  // under the crosshair
    double confidence = 0.0;  // 0..1
    bool operator==(const Aim&) const = default;
};

// provider -> requester, the answer to an aim: what a grab there would take.
struct Target {
    std::optional<RequestId> id;  // the aim's
    FieldPoint point;             // the aim's point
    ContentKind kind = ContentKind::none;
    std::string title;  // display text
    bool operator==(const Target&) const = default;
};

// requester -> provider: take what is at the point.
struct Grab {
    RequestId id;
    FieldPoint point;
    bool operator==(const Grab&) const = default;
};

// provider -> requester, the answer to a grab. url needs `url`; file and
// snapshot need name, mime, size and download; sha256 is optional.
struct Content {
    RequestId id;  // the grab's
    ContentKind kind = ContentKind::none;
    std::string title;                    // display text
    std::optional<std::string> url;       // http: or https:, no spaces or control characters
    std::optional<std::string> name;      // file name: no '/', '\\' or control characters, not "." or ".."
    std::optional<std::string> mime;      // "type/subtype", printable ASCII
    std::optional<std::int64_t> size;     // bytes, 0..2^53 - 1
    std::optional<std::string> sha256;    // 64 lowercase hex digits
    std::optional<std::string> download;  // one-time path on the provider: "/dl/..."
    bool operator==(const Content&) const = default;
};

// Either way. The id is the request's, when the request had one and it could
// be read.
struct Error {
    std::optional<RequestId> id;
    ErrorCode code = ErrorCode::internal;
    std::string message;  // display text, for logs and people
    bool operator==(const Error&) const = default;
};

// requester -> provider: give the screen a URL or a file at the point
// (docs/PROTOCOL.md, "Put"). kind url needs `url`; kind file needs name,
// mime and size, and has sha256 unless the upload names it after the bytes.
struct Put {
    RequestId id;
    FieldPoint point;
    ContentKind kind = ContentKind::url;  // url or file only
    std::string title;                    // display text, may be empty (then left out of the text)
    std::optional<std::string> url;
    std::optional<std::string> name;
    std::optional<std::string> mime;
    std::optional<std::int64_t> size;
    std::optional<std::string> sha256;
    bool operator==(const Put&) const = default;
};

enum class PutState { asking, upload, done };
const char* to_string(PutState state);
enum class PutOutcome { saved, opened };
const char* to_string(PutOutcome outcome);

// provider -> requester: how a put goes on. upload needs `upload` (the path
// to PUT the bytes to); done needs `outcome`, and `name` with outcome saved
// (the name the file was stored under; opened may carry it for a file).
struct PutStatus {
    RequestId id;  // the put's
    PutState status = PutState::asking;
    std::optional<std::string> upload;
    std::optional<PutOutcome> outcome;
    std::optional<std::string> name;
    bool operator==(const PutStatus&) const = default;
};

// New types go at the end: the index is part of type_name's table.
using Message = std::variant<Hello, Welcome, Seeking, Aim, Target, Grab, Content, Error, Put, PutStatus>;

// "hello", "welcome", ...: the message's "type".
const char* type_name(const Message& message);
// hello, seeking, aim, grab and put: what a requester sends. A provider
// answers anything else with bad_request.
bool is_request(const Message& message);

// The JSON text of a message. Display text is made valid UTF-8 and clipped to
// its cap; anything else out of range (a NaN point, a bad URL, an invalid
// field) throws std::invalid_argument naming it: what encode() returns
// always parses.
std::string encode(const Message& message);
// The same without exceptions, for WebAssembly builds (emscripten's default
// turns a throw into an abort): the text, or nullopt and what is wrong in
// `problem`.
std::optional<std::string> try_encode(const Message& message, std::string* problem = nullptr);

// Why a text is not a message, with the code to answer it with.
struct ProtocolError {
    ErrorCode code = ErrorCode::bad_request;
    std::string message;
    std::optional<RequestId> id;  // when the text had a readable one
    bool operator==(const ProtocolError&) const = default;
};

using ParseResult = std::variant<Message, ProtocolError>;

// Never throws. too_large when the text is above limits.max_bytes (checked
// before parsing), unsupported_version for a "v" other than 1, bad_request
// for everything else that is wrong. One path uses an exception inside: a
// welcome's field definition goes through parse_field, which throws on a
// defect (caught here); in a WebAssembly build without -fexceptions that
// throw aborts instead, so only a provider could crash a requester that way.
ParseResult parse_message(std::string_view text, const ParseLimits& limits = {});

// The error message that answers a text that did not parse.
Error to_error(const ProtocolError& error);

// A media type that Content and Put accept: "type/subtype", printable
// ASCII, 3..kMaxMimeBytes bytes.
bool is_mime_type(std::string_view mime);

// A URL that Content accepts: http: or https: (any case), no spaces or
// control characters.
bool is_http_url(std::string_view url);

// A file name that Content accepts: invalid UTF-8 repaired, '/', '\\' and
// control characters replaced by '_', clipped to kMaxFileNameBytes; "file"
// when nothing usable is left.
std::string safe_file_name(std::string_view name);

}  // namespace umf::protocol
