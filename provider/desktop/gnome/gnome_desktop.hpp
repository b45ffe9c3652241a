// GNOME Shell (Mutter) as a desktop: Mutter has no layer shell and gives
// clients neither the window list nor the screen's pixels, so everything
// goes through the umf Shell extension (extension/), asked over the session
// bus. Without it, abilities() says what to do and every query fails fast.
#pragma once

#include <QObject>
#include <chrono>
#include <memory>

#include "provider/desktop/desktop.hpp"

namespace umf::provider {

class GnomeShellClient;

class GnomeDesktop final : public Desktop {
public:
    // Throws DesktopError when there is no session bus. `timeout` bounds
    // every call to the extension.
    explicit GnomeDesktop(std::chrono::milliseconds timeout = std::chrono::milliseconds(2000));
    ~GnomeDesktop() override;

    std::string name() const override { return "gnome"; }
    DesktopAbilities abilities() const override;
    std::vector<DesktopOutput> outputs() const override;
    std::optional<WindowInfo> window_at(double x, double y, const WindowFilter& filter) const override;
    Capture capture(const WindowRect& rect) const override;
    // The screen with the field in it, as a camera sees it (checks, pictures).
    Capture capture_as_shown(const WindowRect& rect) const;
    std::unique_ptr<NewWindowWatch> watch_new_window(const WindowPlacement& placement) const override;
    // `screen` null: the first monitor.
    std::unique_ptr<FieldSurface> make_field_surface(QScreen* screen, ScreenField field,
                                                     const std::vector<std::string>& palette) override;
    void on_abilities_changed(std::function<void()> changed) override;

    // The extension's own connection, for checks of what it shows.
    const GnomeShellClient& shell() const { return *shell_; }

private:
    Capture read_shot(const WindowRect& rect, bool with_field) const;
    std::shared_ptr<GnomeShellClient> shell_;
    std::unique_ptr<QObject> extension_watch_;  // says on the console when the extension stops and comes back
    std::function<void()> abilities_changed_;
};

// For the lead's backend choice.
std::unique_ptr<Desktop> make_gnome_desktop();

}  // namespace umf::provider
