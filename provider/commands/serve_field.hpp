// `umf-provider pair --rotate --field` reaching a running provider (the
// control socket's "field"): the screen's own field as its configuration
// has it now, shown where this provider shows its field and given to the
// service, whose sessions then connect again as after a change of screens.
#pragma once

#include <QImage>
#include <filesystem>
#include <string>

#include "provider/screen/field_source.hpp"
#include "provider/service/control_socket.hpp"

namespace umf::provider {

class BoardWindow;
class OverlayManager;
class Service;

// Where a running provider shows its field.
struct FieldShowing {
    std::filesystem::path config_dir;
    FieldSource& fields;       // the source shown now; replaced when the seed changed
    Service& service;
    OverlayManager* overlay;   // a desktop's screens, whose layout the service follows; else one screen:
    BoardWindow* board_window;  // a board on a screen, painted as `board_image`; null headless
    const QImage& board_image;
    int width, height;
    double module_px;
    std::string screen_name;
};

// On Qt's thread when windows show the field, else on any. A provider that
// shows the shipped field (--shipped-field) keeps it. Throws
// std::runtime_error when the seed cannot be read.
FieldShown show_own_field(const FieldShowing& showing);
// The same from any thread: handed to Qt's when windows show the field.
FieldShown show_own_field_from_any_thread(const FieldShowing& showing);

}  // namespace umf::provider
