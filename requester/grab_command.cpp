#include "requester/grab_command.hpp"

#include <chrono>
#include <filesystem>
#include <string>
#include <vector>

#include "requester/aiming_session.hpp"
#include "requester/cli.hpp"
#include "requester/device_name.hpp"
#include "requester/download.hpp"
#include "requester/download_dir.hpp"
#include "requester/grab_failure.hpp"
#include "requester/open_url.hpp"
#include "requester/transfer_text.hpp"
#include "shared/protocol/messages.hpp"

namespace umf::requester {

const char* const kGrabUsage = R"(umf-requester grab: take what a provider's screen shows where the camera points

usage:
  umf-requester grab [--url URL] [--camera I | --video FILE | --image FILE]
                     [--out DIR] [--open] [--auto] [--no-window] [--timeout S] [--no-switch]

Connects to the provider of the pairing URL (the certificate must have the URL's
fingerprint), finds the provider's marker field in the camera image and grabs
what is shown under the image centre: a link is printed, a file or a snapshot is
downloaded. A preview window shows the camera with a crosshair: a red banner
while the field is not found, a green ring and what a grab would take once it is;
space or Enter grabs, q or Esc quits.

options:
  --url URL       the pairing URL, https://HOST:PORT/#t=TOKEN&fp=FINGERPRINT
                  (umf-provider pair prints it); default the screen kept or used
                  last (umf-requester pair URL keeps one)
  --camera I      camera number I (/dev/videoI); camera 0 when no input is given
  --video FILE    the frames of a video file instead of a camera
  --image FILE    one photo: detect once and grab at once (implies --auto)
  --out DIR       where downloads go (created if missing); default the desktop's
                  download directory (XDG_DOWNLOAD_DIR, else ~/Downloads). An
                  existing file is never replaced: "report (1).pdf" instead
  --open          open a grabbed link with xdg-open
  --auto          grab as soon as the aim holds steady (half a second within half
                  a module) instead of waiting for a key
  --no-window     no preview (also when there is no display); needs --auto
  --timeout S     give up after S seconds; camera default 30
  --no-switch     pointed at another screen than the URL's, say so and stop, rather
                  than switch to it when it is one of the screens kept with pair

Prints one JSON line at the end, progress goes to stderr:
  {"ok":true,"kind":"url","title":"...","point":[u,v],"url":"...","opened":false}
  {"ok":true,"kind":"file","title":"...","point":[u,v],"saved":"/abs/path",
   "name":"...","size":n,"sha256":"...","mime":"..."}          (also "snapshot")
  {"ok":false,"error":{"code":"...","message":"..."}}
error codes: usage, input, output, connection, certificate, unauthorized, timeout,
  protocol, not_found_in_view, another_screen, no_steady_lock, no_grab, cancelled,
  nothing_to_take, download, and the provider's own (not_found, rate_limited,
  bad_request, too_large, internal, unsupported_version).

exit codes: 0 grabbed; 2 wrong usage; 3 the input could not be read or the file not
            written; 4 the provider could not be reached, its certificate did not
            match, it refused the token, or the exchange failed; 5 nothing was
            grabbed (no field in view, no steady aim, nothing at that point,
            the link expired, or cancelled).
)";

namespace {

namespace p = protocol;


// A grab carried through by the requester core: the file it asks for is
// downloaded here, its outcome becomes the JSON line (a link printed and
// opened with --open, a file saved).
class GrabAction {
public:
    GrabAction(AimingSession& session, const GrabOptions& o) : session_(session), o_(o) {}

    PointAction action() {
        PointAction a;
        a.verb = "grab";
        a.download = [this](const p::Content& c) { download(c); };
        a.report = [this](const requester_core::Outcome& outcome, const p::FieldPoint& at) {
            return report(outcome, at);
        };
        return a;
    }

private:
    void download(const p::Content& c) {
        const std::filesystem::path dir = o_.out ? std::filesystem::path(*o_.out) : default_download_dir();
        log("downloading " + *c.name + " (" + std::to_string(*c.size) + " bytes) to " + dir.string());
        const auto started = std::chrono::steady_clock::now();
        saved_ = download_file(session_.connection().url(), {*c.download, *c.name, *c.size, c.sha256}, dir, {},
                               [this](const std::string& line) { log(line); });
        log("saved " + saved_->path.string() + " (" +
            transfer_rate(static_cast<std::uint64_t>(saved_->size), std::chrono::steady_clock::now() - started) + ")");
    }

    Json report(const requester_core::Outcome& outcome, const p::FieldPoint& at) {
        if (!outcome.ok) {
            // The core's own codes keep the names the command always used.
            if (outcome.code == "unreachable") throw GrabFailure("timeout", outcome.message, kConnection);
            if (outcome.code == "protocol") throw GrabFailure("protocol", outcome.message, kConnection);
            const bool nothing = outcome.code == "not_found" || outcome.code == "rate_limited";
            throw GrabFailure(outcome.code, "the provider refused the grab: " + outcome.message,
                              nothing ? kNothing : kConnection);
        }
        const p::Content& c = *outcome.content;
        Json j;
        j["ok"] = true;
        j["kind"] = p::to_string(c.kind);
        j["title"] = c.title;
        j["point"] = point_json(at);
        switch (c.kind) {
            case p::ContentKind::none:
                throw GrabFailure("nothing_to_take",
                                  "nothing to take at that point" + (c.title.empty() ? std::string() : " (" + c.title + ")"),
                                  kNothing);
            case p::ContentKind::url:
                j["url"] = *c.url;
                log("link: " + *c.url);
                j["opened"] = o_.open && open_url(*c.url);
                return j;
            case p::ContentKind::file:
            case p::ContentKind::snapshot:
                j["saved"] = saved_->path.string();
                j["name"] = saved_->name;
                j["size"] = saved_->size;
                j["sha256"] = saved_->sha256;
                if (c.mime) j["mime"] = *c.mime;
                return j;
        }
        throw GrabFailure("protocol", "unknown content kind", kConnection);
    }

    AimingSession& session_;
    const GrabOptions& o_;
    std::optional<SavedFile> saved_;
};

}  // namespace

GrabOptions parse_grab_args(int argc, char** argv, int first) {
    std::vector<std::string> options = kPointingOptionNames, flags = kPointingFlagNames;
    options.push_back("out");
    flags.push_back("open");
    const Args a = parse_args(argc, argv, first, options, flags);
    if (!a.positional.empty()) throw UsageError("grab takes no file arguments; use --image FILE or --video FILE");
    GrabOptions o;
    o.pointing = parse_pointing_args(a, "grab");
    o.out = get(a, "out");
    if (o.out && o.out->empty()) throw UsageError("--out needs a directory");
    o.open = has_flag(a, "open");
    return o;
}

void write_usage_failure(std::FILE* out, const std::string& message) { write_line(out, failure_json("usage", message)); }

int run_grab(const GrabOptions& o, std::FILE* out) {
    std::optional<protocol::FieldPoint> point;
    return run_and_report(
        [&] {
            AimingSession session(o.pointing, client_name());
            try {
                GrabAction grab(session, o);
                return session.run({}, grab.action());
            } catch (...) {
                point = session.acted_point();
                throw;
            }
        },
        point, out);
}

}  // namespace umf::requester
