#include "requester/put_command.hpp"

#include <algorithm>
#include <cctype>
#include <chrono>
#include <stdexcept>
#include <vector>

#include "requester/cli.hpp"
#include "requester/device_name.hpp"
#include "requester/file_digest.hpp"
#include "requester/grab_failure.hpp"
#include "requester/transfer_text.hpp"
#include "requester/upload.hpp"
#include "shared/protocol/media_types.hpp"
#include "shared/protocol/messages.hpp"

namespace umf::requester {

const char* const kPutUsage = R"(umf-requester put: give a provider's screen a file or a link where the camera points

usage:
  umf-requester put FILE|LINK [--url URL] [--title TEXT]
                    [--camera I | --video FILE | --image FILE]
                    [--auto] [--no-window] [--timeout S] [--no-switch]

Connects to the provider of the pairing URL (the certificate must have the URL's
fingerprint), finds the provider's marker field in the camera image and puts FILE
or LINK (an http: or https: URL) at the point under the image centre. The person
at the screen sees a prompt there and accepts or dismisses it (30 s); an accepted
file is sent over a one-time HTTPS link and stored in the screen's download folder
under a name that replaces nothing; a link opens in the screen's browser. The
preview window and its keys are those of grab: space or Enter puts, q or Esc quits.

options:
  --url URL       the pairing URL, https://HOST:PORT/#t=TOKEN&fp=FINGERPRINT; default
                  the screen kept or used last (umf-requester pair URL keeps one)
  --title TEXT    shown in the screen's prompt (at most 512 bytes)
  --camera I      camera number I (/dev/videoI); camera 0 when no input is given
  --video FILE    the frames of a video file instead of a camera
  --image FILE    one photo: detect once and put at once (implies --auto)
  --auto          put as soon as the aim holds steady (half a second within half
                  a module) instead of waiting for a key
  --no-window     no preview (also when there is no display); needs --auto
  --timeout S     give up finding the screen after S seconds; camera default 30
  --no-switch     pointed at another screen than the URL's, say so and stop, rather
                  than switch to it when it is one of the screens kept with pair

This requester names itself to screens with a random device name kept in
$XDG_CONFIG_HOME/umf/requester-device, so a screen told "always accept from this
device" does not ask again.

Prints one JSON line at the end, progress goes to stderr:
  {"ok":true,"kind":"url","point":[u,v],"url":"...","outcome":"opened"}
  {"ok":true,"kind":"file","point":[u,v],"outcome":"saved","name":"report (1).pdf",
   "size":n,"sha256":"..."}              (outcome "opened": saved and opened)
  {"ok":false,"error":{"code":"...","message":"..."}}
error codes: usage, input, connection, certificate, unauthorized, timeout, protocol,
  no_puts, not_found_in_view, another_screen, no_steady_lock, no_put, cancelled, upload, and the
  provider's own (refused, too_large, interrupted, not_found, rate_limited,
  bad_request, internal, unsupported_version).

exit codes: 0 the screen took it; 2 wrong usage; 3 the file could not be read;
            4 the provider could not be reached, its certificate did not match,
            it refused the token, or the exchange or the upload broke off
            (interrupted); 5 nothing was put (the provider takes no puts, no
            field in view, no steady aim, no screen at that point, the person
            dismissed it or did not answer, the file is too large for the screen,
            or cancelled).
)";

namespace {

namespace p = protocol;
namespace fs = std::filesystem;

bool starts_with_scheme(const std::string& text) {
    std::string head = text.substr(0, 8);
    std::transform(head.begin(), head.end(), head.begin(), [](unsigned char c) { return std::tolower(c); });
    return head.rfind("http://", 0) == 0 || head.rfind("https://", 0) == 0;
}

// Why a put ended: the provider's error codes in words, with their exit code.
[[noreturn]] void fail_with(const p::Error& e) {
    const std::string code = p::to_string(e.code);
    switch (e.code) {
        case p::ErrorCode::refused:
            throw GrabFailure(code, "the screen did not take it: " + e.message, kNothing);
        case p::ErrorCode::too_large:
            throw GrabFailure(code, "the file is too large for the screen: " + e.message, kNothing);
        case p::ErrorCode::not_found:
            throw GrabFailure(code, "no screen shows that point: " + e.message, kNothing);
        case p::ErrorCode::rate_limited:
            throw GrabFailure(code, "too many grabs and puts; wait a little: " + e.message, kNothing);
        case p::ErrorCode::interrupted:
            throw GrabFailure(code, "the upload did not arrive whole; nothing was kept: " + e.message, kConnection);
        default:
            throw GrabFailure(code, "the provider refused the put: " + e.message, kConnection);
    }
}

struct FileToPut {
    fs::path path;
    std::string name;
    std::string mime;
    std::int64_t size = 0;
    // Hashed before the put only for a provider that cannot take the hash
    // after the bytes (no "put-hash-after" in its welcome).
    std::optional<FileDigest> digest;
    std::string sha256;  // as the screen checked it, once sent
};

class PutSession {
public:
    PutSession(const PutOptions& o, std::string device) : o_(o), session_(o.pointing, client_name(), std::move(device)) {}

    Json run() {
        if (o_.file) file_ = prepare_file(*o_.file);
        PointAction action;
        action.verb = "put";
        action.put = item();
        action.upload = [this](const std::string& link) { return upload(link); };
        action.report = [this](const requester_core::Outcome& outcome, const p::FieldPoint& at) {
            return report(outcome, at);
        };
        return session_.run(
            [&](const p::Welcome& w) {
                const auto& f = w.features;
                if (std::find(f.begin(), f.end(), p::kFeaturePut) == f.end())
                    throw GrabFailure("no_puts",
                                      "the screen " + w.provider.name +
                                          " takes no puts (it runs with --puts never, or in public mode)",
                                      kNothing);
                if (file_) hash_for(w, *action.put);
            },
            action);
    }

    std::optional<p::FieldPoint> point() const { return session_.acted_point(); }

private:
    requester_core::PutItem item() const {
        requester_core::PutItem item;
        item.title = o_.title;
        if (file_) {
            item.kind = p::ContentKind::file;
            item.name = file_->name;
            item.mime = file_->mime;
            item.size = file_->size;
        } else {
            item.kind = p::ContentKind::url;
            item.url = *o_.url;
        }
        return item;
    }

    static FileToPut prepare_file(const fs::path& path) {
        FileToPut f;
        f.path = path;
        f.name = p::safe_file_name(path.filename().string());
        f.mime = p::media_type_for(f.name);
        std::error_code ec;
        const auto status = fs::status(path, ec);
        if (ec || !fs::is_regular_file(status))
            throw GrabFailure("input", path.string() + (ec ? ": " + ec.message() : std::string(" is not a regular file")),
                              kInputError);
        const auto size = fs::file_size(path, ec);
        if (ec) throw GrabFailure("input", "cannot read " + path.string() + ": " + ec.message(), kInputError);
        f.size = static_cast<std::int64_t>(size);
        log("putting " + f.name + " (" + std::to_string(f.size) + " bytes, " + f.mime + ")");
        return f;
    }

    // The file's SHA-256 goes after its bytes where the screen takes it so
    // (read once, and the offer goes out at once); else it is hashed now,
    // before the put.
    void hash_for(const p::Welcome& welcome, requester_core::PutItem& item) {
        const auto& f = welcome.features;
        item.hash_after = std::find(f.begin(), f.end(), p::kFeaturePutHashAfter) != f.end();
        if (item.hash_after) {
            item.sha256.reset();
            return;
        }
        if (!file_->digest) {
            try {
                file_->digest = digest_file(file_->path);
            } catch (const std::runtime_error& e) {
                throw GrabFailure("input", e.what(), kInputError);
            }
            if (file_->digest->size != file_->size)
                throw GrabFailure("input", file_->path.string() + " changed its size while it was hashed", kInputError);
        }
        item.sha256 = file_->digest->sha256;
    }

    p::PutStatus upload(const std::string& link) {
        if (!file_) throw GrabFailure("protocol", "the provider asked for an upload of a link", kConnection);
        log("accepted; sending " + megabytes(static_cast<std::uint64_t>(file_->size)));
        auto last = std::chrono::steady_clock::now();
        auto shown = last;
        const auto progress = [&](std::int64_t sent, std::int64_t size) {
            const auto now = std::chrono::steady_clock::now();
            if (sent == size || now - shown >= std::chrono::milliseconds(100)) {
                shown = now;
                session_.show_progress("sending " + std::to_string(size ? sent * 100 / size : 100) + " %");
            }
            if (sent < size && now - last < std::chrono::seconds(1)) return;
            last = now;
            log("sent " + megabytes(static_cast<std::uint64_t>(sent)) + " of " + megabytes(static_cast<std::uint64_t>(size)));
        };
        const auto started = std::chrono::steady_clock::now();
        // The digest is there when the put carried the hash (hash_for).
        UploadRequest request{link, file_->path, file_->size, nullptr, !file_->digest};
        if (file_->digest) request.checkpoints = file_->digest->checkpoints;
        auto uploaded = upload_file(session_.connection().url(), request, progress, {},
                                    [this](const std::string& line) { log(line); });
        file_->sha256 = file_->digest ? file_->digest->sha256 : uploaded.sha256;
        log("sent " + transfer_rate(static_cast<std::uint64_t>(file_->size), std::chrono::steady_clock::now() - started));
        return uploaded.status;
    }

    Json report(const requester_core::Outcome& outcome, const p::FieldPoint& at) {
        if (!outcome.ok) {
            // The core's own codes keep the names the command always used.
            if (outcome.code == "unreachable") throw GrabFailure("timeout", outcome.message, kConnection);
            const auto code = p::error_code_from_string(outcome.code);
            if (!code) throw GrabFailure(outcome.code, outcome.message, kConnection);
            fail_with(p::Error{std::nullopt, *code, outcome.message});
        }
        const p::PutStatus& status = *outcome.put;
        if (status.status != p::PutState::done || !status.outcome)
            throw GrabFailure("protocol", "the provider ended the put without an outcome", kConnection);
        Json j;
        j["ok"] = true;
        j["kind"] = file_ ? "file" : "url";
        j["point"] = point_json(at);
        if (!file_) j["url"] = *o_.url;
        j["outcome"] = p::to_string(*status.outcome);
        if (status.name) j["name"] = *status.name;
        if (file_) {
            j["size"] = file_->size;
            j["sha256"] = file_->sha256;
        }
        log(*status.outcome == p::PutOutcome::opened
                ? "the screen opened it" + (status.name ? " (" + *status.name + ")" : std::string())
                : "the screen saved it as " + status.name.value_or("?"));
        return j;
    }

    const PutOptions& o_;
    AimingSession session_;
    std::optional<FileToPut> file_;
};

}  // namespace

PutOptions parse_put_args(int argc, char** argv, int first) {
    std::vector<std::string> options = kPointingOptionNames, flags = kPointingFlagNames;
    options.push_back("title");
    const Args a = parse_args(argc, argv, first, options, flags);
    if (a.positional.size() != 1)
        throw UsageError(a.positional.empty() ? "put needs what to put: a FILE or an http(s) LINK"
                                              : "put takes one FILE or LINK at a time");
    PutOptions o;
    o.pointing = parse_pointing_args(a, "put");
    const std::string& what = a.positional.front();
    if (starts_with_scheme(what)) {
        if (!p::is_http_url(what) || what.size() > p::kMaxUrlBytes)
            throw UsageError("'" + what + "' is not a link a screen can open (http: or https:, no spaces, at most " +
                             std::to_string(p::kMaxUrlBytes) + " bytes)");
        o.url = what;
    } else {
        if (what.empty()) throw UsageError("put needs a FILE or an http(s) LINK, not an empty name");
        o.file = what;
    }
    if (auto t = get(a, "title")) {
        if (t->size() > p::kMaxTitleBytes)
            throw UsageError("--title has " + std::to_string(t->size()) + " bytes; at most " +
                             std::to_string(p::kMaxTitleBytes));
        o.title = *t;
    }
    o.device_file = default_device_file();
    return o;
}

int run_put(const PutOptions& o, std::FILE* out) {
    std::optional<p::FieldPoint> point;
    return run_and_report(
        [&] {
            std::string note;
            const std::string device = device_name(o.device_file, note);
            if (!note.empty()) log(note);
            PutSession session(o, device);
            try {
                return session.run();
            } catch (...) {
                point = session.point();
                throw;
            }
        },
        point, out);
}

}  // namespace umf::requester
