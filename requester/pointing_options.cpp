#include "requester/pointing_options.hpp"

#include <cstdlib>

#include "requester/aiming_session.hpp"  // log

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
    const auto url = get(a, "url");
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
    o.switch_screens = !has_flag(a, "no-switch");
    const int inputs = (get(a, "camera") ? 1 : 0) + (get(a, "video") ? 1 : 0) + (get(a, "image") ? 1 : 0);
    if (inputs > 1) throw UsageError(verb + " reads one of --camera, --video or --image");
    if (auto c = get(a, "camera")) o.camera_index = parse_camera(*c);
    if (auto v = get(a, "video")) {
        o.input = FrameInput::video;
        o.path = *v;
    }
    if (auto i = get(a, "image")) {
        o.input = FrameInput::image;
        o.path = *i;
    }
    if ((o.input != FrameInput::camera) && o.path.empty()) throw UsageError("--video and --image need a file name");
    o.auto_act = has_flag(a, "auto") || o.input == FrameInput::image;
    if (auto t = get(a, "timeout")) o.timeout_s = parse_seconds(*t);
    o.window = o.input != FrameInput::image && !has_flag(a, "no-window") && has_display();
    if (o.input != FrameInput::image && !o.window && !o.auto_act)
        throw UsageError(std::string(has_flag(a, "no-window") ? "with --no-window" : "without a display ($DISPLAY is unset)") +
                         " no key can say when to " + verb + ": add --auto to " + verb + " on a steady aim");
    return o;
}

}  // namespace umf::requester
