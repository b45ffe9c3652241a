#include "provider/desktop/gnome/gnome_desktop.hpp"

#include <QImage>
#include <filesystem>
#include <iostream>

#include "provider/desktop/gnome/gnome_extension.hpp"
#include "provider/desktop/gnome/gnome_field_surface.hpp"
#include "provider/desktop/gnome/gnome_shell_client.hpp"
#include "provider/desktop/gnome/gnome_window_watch.hpp"
#include "provider/desktop/gnome/private_folder.hpp"

namespace umf::provider {

namespace {

constexpr const char* kInstallHint = "run: umf-provider gnome install, then log out and in";

// Whether the extension's files are where the shell looks for a user's.
bool extension_installed() {
    std::filesystem::path data;
    if (const char* xdg = std::getenv("XDG_DATA_HOME"); xdg && *xdg) data = xdg;
    else if (const char* home = std::getenv("HOME"); home && *home) data = std::filesystem::path(home) / ".local/share";
    std::error_code ec;
    return !data.empty() &&
           std::filesystem::exists(data / "gnome-shell/extensions" / std::string(kGnomeExtensionUuid) / "metadata.json", ec);
}

}  // namespace

GnomeDesktop::GnomeDesktop(std::chrono::milliseconds timeout) : shell_(std::make_shared<GnomeShellClient>(timeout)) {
    // Only changes are news: the name taken while the shell starts is not.
    extension_watch_ = shell_->watch_extension([this, was_running = shell_->extension_present()](bool running) mutable {
        if (running == was_running) return;
        was_running = running;
        if (running)
            std::cerr << "umf-provider: the umf GNOME Shell extension runs again: the field, windows and snapshots are back\n";
        else
            std::cerr << "umf-provider: the umf GNOME Shell extension stopped (disabled, or GNOME Shell restarted): no "
                         "field, windows or snapshots until it runs again; boards, shares and puts go on\n";
        if (abilities_changed_) abilities_changed_();
    });
}

void GnomeDesktop::on_abilities_changed(std::function<void()> changed) { abilities_changed_ = std::move(changed); }

GnomeDesktop::~GnomeDesktop() = default;

DesktopAbilities GnomeDesktop::abilities() const {
    DesktopAbilities a;
    if (!shell_->extension_present()) {
        a.notes.push_back(extension_installed()
                              ? "the umf GNOME Shell extension is installed but not running (disabled, or installed "
                                "since login): run: umf-provider gnome install, then log out and in"
                              : std::string("the umf GNOME Shell extension is not installed: ") + kInstallHint);
        return a;
    }
    try {
        const auto version = shell_->version();
        if (version.api != kGnomeShellApi) {
            a.notes.push_back("the umf GNOME Shell extension speaks version " + std::to_string(version.api) +
                              ", this provider " + std::to_string(kGnomeShellApi) + ": " + kInstallHint);
            return a;
        }
    } catch (const DesktopError& e) {
        a.notes.push_back(std::string(e.what()) + "; " + kInstallHint);
        return a;
    }
    a.field = a.windows = a.snapshots = a.placement = true;
    return a;
}

std::vector<DesktopOutput> GnomeDesktop::outputs() const { return shell_->monitors(); }

std::optional<WindowInfo> GnomeDesktop::window_at(double x, double y, const WindowFilter& filter) const {
    try {
        return shell_->window_at(x, y, filter);
    } catch (const DesktopError& e) {
        if (const char* debug = std::getenv("UMF_DEBUG"); debug && *debug)
            std::cerr << "umf-provider: window at " << x << "," << y << ": " << e.what() << "\n";
        return std::nullopt;
    }
}

Capture GnomeDesktop::capture(const WindowRect& rect) const { return read_shot(rect, false); }

Capture GnomeDesktop::capture_as_shown(const WindowRect& rect) const { return read_shot(rect, true); }

Capture GnomeDesktop::read_shot(const WindowRect& rect, bool with_field) const {
    if (rect.empty()) throw DesktopError("an empty rectangle to capture");
    const auto folder = private_runtime_folder();
    const std::string name = with_field ? shell_->screen_as_shown(rect) : shell_->snapshot(rect);
    if (name.find('/') != std::string::npos || name.empty() || name[0] == '.')
        throw DesktopError("the umf GNOME Shell extension named a snapshot outside its folder: " + name);
    const auto path = folder / name;
    QImage image(QString::fromStdString(path.string()), "PNG");
    std::error_code ec;
    std::filesystem::remove(path, ec);
    if (image.isNull()) throw DesktopError("the snapshot " + path.string() + " could not be read");
    image = image.convertToFormat(QImage::Format_RGB32);
    Capture out;
    out.width = image.width();
    out.height = image.height();
    out.pixels.resize(static_cast<std::size_t>(out.width) * out.height);
    for (int y = 0; y < out.height; ++y) {
        const auto* row = reinterpret_cast<const QRgb*>(image.constScanLine(y));
        for (int x = 0; x < out.width; ++x) out.pixels[static_cast<std::size_t>(y) * out.width + x] = 0xff000000u | row[x];
    }
    return out;
}

std::unique_ptr<NewWindowWatch> GnomeDesktop::watch_new_window(const WindowPlacement& placement) const {
    try {
        return std::make_unique<GnomeNewWindowWatch>(shell_, placement);
    } catch (const DesktopError& e) {
        std::cerr << "umf-provider: cannot place the new window: " << e.what() << "\n";
        return nullptr;
    }
}

std::unique_ptr<FieldSurface> GnomeDesktop::make_field_surface(QScreen* screen, ScreenField field,
                                                               const std::vector<std::string>& palette) {
    try {
        return std::make_unique<GnomeFieldSurface>(shell_, screen, std::move(field), palette);
    } catch (const DesktopError& e) {
        std::cerr << "umf-provider: no field on GNOME Shell: " << e.what() << "\n";
        return nullptr;
    }
}

std::unique_ptr<Desktop> make_gnome_desktop() { return std::make_unique<GnomeDesktop>(); }

}  // namespace umf::provider
