// The provider's tray icon and its menu: the overlay on or off, the preset,
// the tuning window, the pairing QR code, start at login, quit. Desktops without a tray
// (some tiling window managers, GNOME without an extension) still run the
// provider: callers check available() and offer the same through the
// command line instead.
#pragma once

#include <QIcon>
#include <functional>
#include <memory>
#include <string>
#include <vector>

class QAction;
class QActionGroup;
class QMenu;
class QSystemTrayIcon;

namespace umf::provider {

struct TrayCallbacks {
    std::function<void(bool on)> overlay_toggled;
    std::function<void(const std::string& preset)> preset_chosen;
    std::function<void()> tune;
    std::function<void()> pairing_qr;
    // "Start at login" is offered when this is set; it gets the new state.
    std::function<void(bool on)> start_at_login;
    std::function<void()> quit;
};

class TrayMenu {
public:
    // Needs a QApplication. The icon is not shown until show(). `status`
    // (what works on this desktop) heads the menu and is the tooltip.
    TrayMenu(const std::vector<std::string>& presets, const std::string& current_preset, bool overlay_on,
             TrayCallbacks callbacks, const std::string& status = {});
    // A desktop that shows no field: the status, the pairing QR code, quit.
    TrayMenu(TrayCallbacks callbacks, const std::string& status);
    ~TrayMenu();
    TrayMenu(const TrayMenu&) = delete;
    TrayMenu& operator=(const TrayMenu&) = delete;

    static bool available();
    void show();

    // Follow changes made elsewhere (the tuning window, the command line)
    // without calling back.
    void set_presets(const std::vector<std::string>& presets, const std::string& current_preset);
    void set_overlay_on(bool on);
    void set_start_at_login(bool on);
    // What works on this desktop changed: the line heading the menu and the
    // tooltip say it now (empty: neither says anything).
    void set_status(const std::string& status);

    QMenu* menu() const { return menu_.get(); }
    QSystemTrayIcon* tray_icon() const { return tray_.get(); }

private:
    TrayCallbacks callbacks_;
    std::unique_ptr<QMenu> menu_;
    std::unique_ptr<QSystemTrayIcon> tray_;
    QAction* overlay_ = nullptr;
    QAction* start_at_login_ = nullptr;
    QMenu* presets_ = nullptr;
    QActionGroup* preset_group_ = nullptr;
    QAction* status_ = nullptr;  // the line heading the menu
    QAction* status_separator_ = nullptr;

    void add_common();
};

// A few modules of a field with a pulse ring around them, drawn rather than
// loaded so the provider ships no image files.
QIcon field_icon(int size = 64);

}  // namespace umf::provider
