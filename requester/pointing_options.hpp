// What grab and put are told about pointing: the screen (its pairing URL,
// or the screen kept or used last), the frames (a camera, a video, a
// photo), and how to act and when to give up.
#pragma once

#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "requester/cli.hpp"
#include "requester/paired_screens.hpp"
#include "shared/protocol/pairing_url.hpp"

namespace umf::requester {

enum class FrameInput { camera, video, image };

struct PointingOptions {
    protocol::PairingUrl url;
    // The screens kept with `umf-requester pair`, used last first, and
    // their file (empty: none kept); pointed at another screen, the session
    // switches to the one of them in view, unless not `switch_screens`.
    std::vector<PairedScreen> paired;
    std::filesystem::path paired_file;
    bool switch_screens = true;
    FrameInput input = FrameInput::camera;
    int camera_index = 0;
    std::string path;                 // the video or image file
    bool auto_act = false;            // act on a steady lock, no key needed
    bool window = false;              // show the preview (decided from --no-window and $DISPLAY)
    std::optional<double> timeout_s;  // give up after this long (camera: 30 s by default)
};

// The options grab and put share: --url (default: the screen kept or
// used last), --camera, --video, --image, --auto, --no-window, --timeout
// and --no-switch, already parsed into `a` (which must have accepted them).
// `verb` names the command in messages. Throws UsageError.
PointingOptions parse_pointing_args(const Args& a, const std::string& verb);

// The option names parse_pointing_args reads, for parse_args.
extern const std::vector<std::string> kPointingOptionNames;
extern const std::vector<std::string> kPointingFlagNames;

}  // namespace umf::requester
