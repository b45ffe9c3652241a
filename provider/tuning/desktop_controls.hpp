// What the person at the desk controls the running provider with: the tray
// icon's menu (what the desktop allows, overlay on/off, preset, tuning,
// pairing QR code, start at login, quit) and the tuning window, which changes the overlay
// live. Without a system tray (or with --tune) the tuning window is opened on
// request at start-up. On a desktop that shows no field the tray has the
// status line, the pairing QR code and quit.
#pragma once

#include <QImage>
#include <QLabel>
#include <filesystem>
#include <memory>
#include <string>

#include "provider/field_overlay/overlay_manager.hpp"
#include "provider/tuning/preset_store.hpp"
#include "provider/tuning/tray_menu.hpp"
#include "provider/tuning/tuning_window.hpp"

namespace umf::provider {

// The pairing URL's QR code as an image, `scale` pixels a module, with a
// quiet zone of 4 modules.
QImage pairing_qr_image(const std::string& url, int scale = 6);

class DesktopControls {
public:
    // Needs a QApplication; the manager (null: no field here) must outlive
    // the controls. `status` says what works on this desktop.
    DesktopControls(OverlayManager* overlay, const std::string& status, std::string presets_file,
                    std::string pairing_url, std::function<void()> quit);
    bool has_tray() const { return tray_ != nullptr; }
    ~DesktopControls();

    void show_tuning();
    void show_pairing();
    // What works on this desktop changed: the tray says it now.
    void set_status(const std::string& status);

private:
    OverlayManager* overlay_;
    PresetStore store_;
    std::string pairing_url_;
    std::unique_ptr<TrayMenu> tray_;
    std::unique_ptr<TuningWindow> tuning_;
    std::unique_ptr<QLabel> pairing_;

    // The tray's "Start at login": the autostart entry (`entry`) written or
    // removed; a failure is said on the console and the menu shows what is so.
    void start_at_login(const std::filesystem::path& entry, bool on);
};

}  // namespace umf::provider
