#include "provider/desktop/gnome/gnome_field_surface.hpp"

#include <QImage>
#include <QScreen>
#include <algorithm>
#include <filesystem>
#include <iostream>

#include "provider/desktop/gnome/gnome_shell_client.hpp"
#include "provider/desktop/gnome/private_folder.hpp"
#include "provider/screen/aim_mark.hpp"
#include "provider/screen/board_window.hpp"

namespace umf::provider {

std::optional<int> monitor_for_screen(const std::vector<DesktopOutput>& monitors, const std::string& screen_name,
                                      const WindowRect& screen_rect) {
    if (monitors.empty()) return std::nullopt;
    for (std::size_t i = 0; i < monitors.size(); ++i)
        if (!screen_name.empty() && monitors[i].name == screen_name) return static_cast<int>(i);
    for (std::size_t i = 0; i < monitors.size(); ++i)
        if (!screen_rect.empty() && monitors[i].rect == screen_rect) return static_cast<int>(i);
    return 0;
}

GnomeFieldSurface::GnomeFieldSurface(std::shared_ptr<const GnomeShellClient> shell, QScreen* screen, ScreenField field,
                                     const std::vector<std::string>& palette)
    : shell_(std::move(shell)), screen_(screen), field_(std::move(field)), palette_(palette) {
    monitor_ = find_monitor();
    private_runtime_folder();  // throws when it cannot be used
    send_layer();
    extension_watch_ = shell_->watch_extension([this](bool running) {
        aim_mark_.reset();  // gone with the extension: made again at the next aim
        if (running) send_layer();
    });
}

GnomeFieldSurface::~GnomeFieldSurface() { shell_->drop_field(monitor_); }

int GnomeFieldSurface::find_monitor() const {
    std::string name;
    WindowRect rect;
    if (screen_) {
        name = screen_->name().toStdString();
        const QRect g = screen_->geometry();
        rect = {g.x(), g.y(), g.width(), g.height()};
    }
    const auto index = monitor_for_screen(shell_->monitors(), name, rect);
    if (!index) throw DesktopError("GNOME Shell reports no monitor");
    return *index;
}

void GnomeFieldSurface::send_layer() {
    try {
        const auto folder = private_runtime_folder();
        const std::string name = "field-" + std::to_string(monitor_) + ".png";
        const auto partial = folder / (name + ".part");
        // Fast compression: the image is read once, a few ms later.
        if (!field_layer(field_, palette_).save(QString::fromStdString(partial.string()), "PNG", 90))
            throw DesktopError("cannot write " + partial.string());
        std::filesystem::rename(partial, folder / name);
        shell_->set_field(monitor_, name);
    } catch (const std::exception& e) {
        std::cerr << "umf-provider: the field on GNOME Shell: " << e.what() << "\n";
        return;
    }
    // A reloaded layer keeps the state it had.
    shell_->send_field_opacity(monitor_, pulse_);
    shell_->send_field_focus(
        monitor_, focus_centre_ ? std::optional(std::pair{focus_centre_->x(), focus_centre_->y()}) : std::nullopt,
        focus_radius_);
    shell_->send_field_visible(monitor_, visible_);
}

void GnomeFieldSurface::set_field(ScreenField field, const std::vector<std::string>& palette) {
    field_ = std::move(field);
    palette_ = palette;
    send_layer();
}

void GnomeFieldSurface::cover_screen() {
    try {
        const int now = find_monitor();
        if (now == monitor_) return;
        aim_mark_.reset();
        shell_->drop_field(monitor_);
        monitor_ = now;
        send_layer();
    } catch (const DesktopError& e) {
        std::cerr << "umf-provider: the field on GNOME Shell: " << e.what() << "\n";
    }
}

void GnomeFieldSurface::set_opacity(double opacity) {
    opacity = std::clamp(opacity, 0.0, 1.0);
    if (opacity == pulse_) return;
    pulse_ = opacity;
    shell_->send_field_opacity(monitor_, pulse_);
}

void GnomeFieldSurface::set_focus(std::optional<QPointF> centre_px, double radius_px) {
    radius_px = std::max(0.0, radius_px);
    if (centre_px == focus_centre_ && radius_px == focus_radius_) return;
    focus_centre_ = centre_px;
    focus_radius_ = radius_px;
    shell_->send_field_focus(monitor_, centre_px ? std::optional(std::pair{centre_px->x(), centre_px->y()}) : std::nullopt,
                             radius_px);
}

void GnomeFieldSurface::set_aim_mark(std::optional<QPointF> point_px, const QString& title) {
    if (!point_px) {
        drop_aim_mark();
        return;
    }
    std::string file;
    if (!aim_mark_ || aim_mark_->title != title) {
        const AimMark mark = aim_mark(title, 1.0);
        try {
            const auto folder = private_runtime_folder();
            // Three names in turn: the image written over was sent two
            // titles ago and read long since, never the one being read.
            aim_mark_images_ = (aim_mark_images_ + 1) % 3;
            file = "aim-mark-" + std::to_string(monitor_) + "-" + std::to_string(aim_mark_images_) + ".png";
            const auto partial = folder / (file + ".part");
            if (!mark.image.save(QString::fromStdString(partial.string()), "PNG", 90))
                throw DesktopError("cannot write " + partial.string());
            std::filesystem::rename(partial, folder / file);
        } catch (const std::exception& e) {
            std::cerr << "umf-provider: the aim mark on GNOME Shell: " << e.what() << "\n";
            return;
        }
        aim_mark_ = ShownAimMark{title, mark.ring_centre, {}};
    }
    const QPointF corner = *point_px - aim_mark_->ring_centre;
    if (file.empty() && corner == aim_mark_->corner) return;
    aim_mark_->corner = corner;
    shell_->send_aim_mark(monitor_, file, corner.x(), corner.y());
}

void GnomeFieldSurface::drop_aim_mark() {
    if (!aim_mark_) return;
    aim_mark_.reset();
    shell_->send_drop_aim_mark(monitor_);
}

void GnomeFieldSurface::show() {
    visible_ = true;
    shell_->send_field_visible(monitor_, true);
}

void GnomeFieldSurface::hide() {
    visible_ = false;
    shell_->send_field_visible(monitor_, false);
}

}  // namespace umf::provider
