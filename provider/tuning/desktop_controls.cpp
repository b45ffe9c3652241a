#include "provider/tuning/desktop_controls.hpp"

#include <QPainter>
#include <QPixmap>
#include <iostream>
#include <stdexcept>

#include "provider/desktop/autostart.hpp"
#include "provider/service/pairing_qr.hpp"

namespace umf::provider {

QImage pairing_qr_image(const std::string& url, int scale) {
    const auto modules = qr_modules(url);
    const int n = static_cast<int>(modules.size()), quiet = 4;
    QImage image((n + 2 * quiet) * scale, (n + 2 * quiet) * scale, QImage::Format_RGB32);
    image.fill(Qt::white);
    QPainter painter(&image);
    for (int y = 0; y < n; ++y)
        for (int x = 0; x < n; ++x)
            if (modules[y][x]) painter.fillRect((x + quiet) * scale, (y + quiet) * scale, scale, scale, Qt::black);
    return image;
}

namespace {

std::vector<std::string> names_of(const PresetStore& store) {
    std::vector<std::string> names;
    for (const auto& p : store.list()) names.push_back(p.name);
    return names;
}

}  // namespace

DesktopControls::DesktopControls(OverlayManager* overlay, const std::string& status, std::string presets_file,
                                 std::string pairing_url, std::function<void()> quit)
    : overlay_(overlay), store_(std::move(presets_file)), pairing_url_(std::move(pairing_url)) {
    TrayCallbacks callbacks;
    if (overlay_) {
        callbacks.overlay_toggled = [this](bool on) { overlay_->set_visible(on); };
        callbacks.preset_chosen = [this](const std::string& name) {
            if (store_.contains(name)) overlay_->set_preset(store_.get(name));
        };
        callbacks.tune = [this] { show_tuning(); };
    }
    callbacks.pairing_qr = [this] { show_pairing(); };
    callbacks.quit = std::move(quit);
    const auto autostart = autostart_entry_path();
    if (!autostart.empty()) callbacks.start_at_login = [this, autostart](bool on) { start_at_login(autostart, on); };
    if (TrayMenu::available()) {
        tray_ = overlay_ ? std::make_unique<TrayMenu>(names_of(store_), overlay_->preset().name, overlay_->visible(),
                                                      callbacks, status)
                         : std::make_unique<TrayMenu>(callbacks, status);
        tray_->set_start_at_login(autostart_enabled(autostart));
        tray_->show();
    }
}

DesktopControls::~DesktopControls() = default;

void DesktopControls::set_status(const std::string& status) {
    if (tray_) tray_->set_status(status);
}

void DesktopControls::show_tuning() {
    if (!overlay_) return;
    if (!tuning_) {
        tuning_ = std::make_unique<TuningWindow>(store_, overlay_->preset().name, [this](const overlay::Preset& p) {
            overlay_->set_preset(p);
            if (tray_) tray_->set_presets(names_of(store_), p.name);
        });
    }
    tuning_->show();
    tuning_->raise();
}

void DesktopControls::start_at_login(const std::filesystem::path& entry, bool on) {
    try {
        set_autostart_for_this_program(entry, on);
        std::cerr << "umf-provider: " << (on ? "starts at login (" + entry.string() + ")" : "no longer starts at login")
                  << "\n";
    } catch (const std::exception& e) {
        std::cerr << "umf-provider: start at login: " << e.what() << "\n";
        // The menu shows what is so, not what was asked for.
        if (tray_) tray_->set_start_at_login(autostart_enabled(entry));
    }
}

void DesktopControls::show_pairing() {
    if (!pairing_) {
        pairing_ = std::make_unique<QLabel>();
        pairing_->setWindowTitle("umf: scan to pair");
        pairing_->setPixmap(QPixmap::fromImage(pairing_qr_image(pairing_url_)));
    }
    pairing_->show();
    pairing_->raise();
}

}  // namespace umf::provider
