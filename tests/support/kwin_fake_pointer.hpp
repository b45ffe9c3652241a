// A pointer of the test's own in a KWin session, through KWin's fake input
// protocol (protocols/kde-fake-input.xml): it moves and clicks as a mouse
// would, so a click lands on whatever KWin finds under the point, through
// the field's layer surface when that takes no input. KWin offers the
// protocol only to a program whose installed desktop file lists
// org_kde_kwin_fake_input under X-KDE-Wayland-Interfaces
// (install_application), and reads such files when a client connects.
#pragma once

#include <linux/input-event-codes.h>
#include <wayland-client.h>

#include <cstring>
#include <stdexcept>
#include <string>

#include "kde-fake-input-client-protocol.h"

namespace umf::test {

class KWinFakePointer {
public:
    // Throws std::runtime_error when the display cannot be reached.
    explicit KWinFakePointer(const std::string& display) : display_(wl_display_connect(display.c_str())) {
        if (!display_) throw std::runtime_error("cannot connect to the Wayland display " + display);
        registry_ = wl_display_get_registry(display_);
        wl_registry_add_listener(registry_, &kRegistryListener, this);
        wl_display_roundtrip(display_);
        if (fake_) {
            org_kde_kwin_fake_input_authenticate(fake_, "umf tests", "clicks through the field in the tests");
            wl_display_roundtrip(display_);
        }
    }
    ~KWinFakePointer() {
        if (fake_) org_kde_kwin_fake_input_destroy(fake_);
        wl_registry_destroy(registry_);
        wl_display_disconnect(display_);
    }
    KWinFakePointer(const KWinFakePointer&) = delete;
    KWinFakePointer& operator=(const KWinFakePointer&) = delete;

    // Whether KWin offered the protocol (at version 3 or later, which moves
    // the pointer to a place) to this connection.
    bool available() const { return fake_ != nullptr; }

    // The left button pressed and released at (x, y).
    void click(double x, double y) {
        if (!fake_) throw std::runtime_error("KWin offers no fake input to this program");
        org_kde_kwin_fake_input_pointer_motion_absolute(fake_, wl_fixed_from_double(x), wl_fixed_from_double(y));
        org_kde_kwin_fake_input_button(fake_, BTN_LEFT, 1);
        org_kde_kwin_fake_input_button(fake_, BTN_LEFT, 0);
        wl_display_roundtrip(display_);
    }

private:
    static void global(void* data, wl_registry* registry, uint32_t name, const char* interface, uint32_t version) {
        auto* self = static_cast<KWinFakePointer*>(data);
        if (std::strcmp(interface, org_kde_kwin_fake_input_interface.name) == 0 && version >= 3)
            self->fake_ = static_cast<org_kde_kwin_fake_input*>(
                wl_registry_bind(registry, name, &org_kde_kwin_fake_input_interface, std::min(version, 4u)));
    }
    static void global_remove(void*, wl_registry*, uint32_t) {}
    static constexpr wl_registry_listener kRegistryListener{&KWinFakePointer::global, &KWinFakePointer::global_remove};

    wl_display* display_;
    wl_registry* registry_ = nullptr;
    org_kde_kwin_fake_input* fake_ = nullptr;
};

}  // namespace umf::test
