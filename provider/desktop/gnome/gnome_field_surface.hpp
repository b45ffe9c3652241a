// The field over one monitor on GNOME Shell: an actor of the umf extension
// above all windows, never reactive. The layer image goes over once as a PNG
// in the private folder (a new field, or the monitor moved); the pulse, the
// focus circle and hide/show are small calls sent without waiting.
#pragma once

#include <QObject>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "provider/desktop/desktop.hpp"

namespace umf::provider {

class GnomeShellClient;

// The index of the monitor that shows `screen`: same name, else same
// rectangle, else the first; nullopt when there are no monitors.
std::optional<int> monitor_for_screen(const std::vector<DesktopOutput>& monitors, const std::string& screen_name,
                                      const WindowRect& screen_rect);

class GnomeFieldSurface final : public FieldSurface {
public:
    // Throws DesktopError when the extension cannot show it.
    GnomeFieldSurface(std::shared_ptr<const GnomeShellClient> shell, QScreen* screen, ScreenField field,
                      const std::vector<std::string>& palette);
    ~GnomeFieldSurface() override;

    const ScreenField& screen_field() const override { return field_; }
    void set_field(ScreenField field, const std::vector<std::string>& palette) override;
    void cover_screen() override;
    void set_opacity(double opacity) override;
    double pulse_opacity() const override { return pulse_; }
    void set_focus(std::optional<QPointF> centre_px, double radius_px) override;
    void set_aim_mark(std::optional<QPointF> point_px, const QString& title) override;
    void show() override;
    void hide() override;
    bool is_visible() const override { return visible_; }

    int monitor() const { return monitor_; }

private:
    int find_monitor() const;
    // Writes the layer and has the extension load it; what fails is said on
    // the console (the Qt thread must not throw).
    void send_layer();
    void drop_aim_mark();

    // The mark shown where a phone points: its image is written once per
    // title, a move only places it again.
    struct ShownAimMark {
        QString title;
        QPointF ring_centre;  // in the image
        QPointF corner;       // on the monitor, physical pixels
    };

    std::shared_ptr<const GnomeShellClient> shell_;
    QScreen* screen_;
    ScreenField field_;
    std::vector<std::string> palette_;
    int monitor_ = 0;
    double pulse_ = 0.0;
    std::optional<QPointF> focus_centre_;
    double focus_radius_ = 0.0;
    bool visible_ = false;
    std::optional<ShownAimMark> aim_mark_;
    int aim_mark_images_ = 0;  // which of three names the last image took
    // The extension started again (enabled, or the shell restarted) shows
    // nothing until told: the layer and its state are sent again.
    std::unique_ptr<QObject> extension_watch_;
};

}  // namespace umf::provider
