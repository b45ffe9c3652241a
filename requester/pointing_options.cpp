#include "pointing_options.hpp"

#include <cstdlib>

#include "aiming_session.hpp"  // log

namespace umf::requester {

namespace {

bool has_display() {
    for (const char* name : {"DISPLAY", "WAYLAND_DISPLAY"})
        if (const char* v = std::getenv(name); v && *v) return true;
    return false;
}

int parse_camera(const std::string& text) {
    if (text.empty() || text.size() > 3 || text.find_first_not_of("0123456789") != std::string::npos)
        throw UsageError("--camera must be a camera number 0..999, not '" + text + "'");
    return std::stoi(text);
}

}  // namespace

const std::vector<std::string> kPointingOptionNames = {"url", "camera", "video", "image", "timeout"};
const std::vector<std::string> kPointingFlagNames = {"auto", "no-window", "no-switch"};

PointingOptions parse_pointing_args(const Args& a, const std::string& verb) {
    PointingOptions o;
    const auto url = a.get("url");
    o.paired_file = default_paired_screens_file();
    try {
        o.paired = read_paired_screens(o.paired_file);
    } catch (const InputError& e) {
        if (!url) throw UsageError(std::string(e.what()) + "; or give --url URL");
        log(std::string(e.what()) + "; no switching to the screens kept there");
        o.paired_file.clear();
    }
    if (!url && o.paired.empty())
        throw UsageError(verb + " needs --url URL, the provider's pairing URL (umf-provider pair prints it), "
                                "or a screen kept with umf-requester pair URL");
    if (url) {
        try {
            o.url = protocol::parse_pairing_url(*url);
        } catch (const protocol::PairingUrlError& e) {
            throw UsageError(std::string("--url: ") + e.what());
        }
    } else {
        o.url = o.paired.front().url;
    }
    o.switch_screens = !a.has_flag("no-switch");
    const int inputs = (a.get("camera") ? 1 : 0) + (a.get("video") ? 1 : 0) + (a.get("image") ? 1 : 0);
    if (inputs > 1) throw UsageError(verb + " reads one of --camera, --video or --image");
    if (auto c = a.get("camera")) o.camera_index = parse_camera(*c);
    if (auto v = a.get("video")) {
        o.input = FrameInput::video;
        o.path = *v;
    }
    if (auto i = a.get("image")) {
        o.input = FrameInput::image;
        o.path = *i;
    }
    if ((o.input != FrameInput::camera) && o.path.empty()) throw UsageError("--video and --image need a file name");
    o.auto_act = a.has_flag("auto") || o.input == FrameInput::image;
    if (auto t = a.get("timeout")) o.timeout_s = parse_seconds(*t);
    o.window = o.input != FrameInput::image && !a.has_flag("no-window") && has_display();
    if (o.input != FrameInput::image && !o.window && !o.auto_act)
        throw UsageError(std::string(a.has_flag("no-window") ? "with --no-window" : "without a display ($DISPLAY is unset)") +
                         " no key can say when to " + verb + ": add --auto to " + verb + " on a steady aim");
    return o;
}

}  // namespace umf::requester
