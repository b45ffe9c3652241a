// One field over every screen of a desktop, so that a field point names its
// screen as well as the place on it. The field is laid over the screens'
// bounding box in the desktop's (X11 root window's) pixels; each screen shows
// the part of the field that falls on it, and since screens do not overlap,
// neither do their parts (the welcome's screens). One screen alone gets
// exactly what screen_field_for gives it.
//
// Screens of different pixel densities want different module sizes, so one
// geometric field cannot serve them: each then shows its own columns of the
// field at its own module size, in the desktop's left-to-right order. Where
// the shipped fields are too small for that, every module grows by the same
// factor until they fit.
#pragma once

#include <string>
#include <vector>

#include "provider/screen/screen_field.hpp"
#include "shared/overlay/placement.hpp"

namespace umf::provider {

struct DesktopScreen {
    std::string name;
    int x = 0, y = 0;  // top-left in desktop pixels
    int width = 0, height = 0;
    double module_px = 0.0;  // wanted, in this screen's pixels (screen_field_for); 0: what covers
};

struct LaidOutScreen {
    DesktopScreen screen;
    ScreenField field;          // the whole field, placed in this screen's own pixels
    overlay::FieldArea region;  // the field points this screen shows
};

struct DesktopLayout {
    Field field;
    std::string file;  // the shipped field it came from
    std::vector<LaidOutScreen> screens;
};

// Throws std::invalid_argument for no screens, an empty or oversized one,
// screens that overlap, or a screen the field does not reach; and
// std::runtime_error when the shipped field cannot be loaded.
DesktopLayout lay_out_desktop(const std::vector<DesktopScreen>& screens, const FieldSource& source = {});

}  // namespace umf::provider
