#include "provider/tuning/tray_menu.hpp"

#include <QAction>
#include <QActionGroup>
#include <QMenu>
#include <QPainter>
#include <QSignalBlocker>
#include <QSystemTrayIcon>

namespace umf::provider {

QIcon field_icon(int size) {
    QPixmap pm(size, size);
    pm.fill(Qt::transparent);
    QPainter p(&pm);
    p.setRenderHint(QPainter::Antialiasing);
    // Modules of a 4 x 4 window of the binary field, so the icon reads as
    // "the field" at tray size.
    static constexpr int kModules[4][4] = {{1, 0, 1, 1}, {0, 1, 0, 0}, {1, 1, 0, 1}, {0, 1, 1, 0}};
    const double margin = size * 0.18, cell = (size - 2 * margin) / 4.0;
    p.fillRect(QRectF(margin, margin, 4 * cell, 4 * cell), QColor(0xf2, 0xf2, 0xf2));
    for (int r = 0; r < 4; ++r)
        for (int c = 0; c < 4; ++c)
            if (kModules[r][c]) p.fillRect(QRectF(margin + c * cell, margin + r * cell, cell, cell), QColor(0x20, 0x20, 0x20));
    p.setPen(QPen(QColor(0x2f, 0x80, 0xed), size * 0.07));
    p.drawEllipse(QRectF(size * 0.06, size * 0.06, size * 0.88, size * 0.88));
    p.end();
    return QIcon(pm);
}

TrayMenu::TrayMenu(const std::vector<std::string>& presets, const std::string& current_preset, bool overlay_on,
                   TrayCallbacks callbacks, const std::string& status)
    : callbacks_(std::move(callbacks)), menu_(std::make_unique<QMenu>()), tray_(std::make_unique<QSystemTrayIcon>()) {
    overlay_ = menu_->addAction("Overlay on");
    overlay_->setCheckable(true);
    overlay_->setChecked(overlay_on);
    QObject::connect(overlay_, &QAction::toggled, menu_.get(), [this](bool on) {
        if (callbacks_.overlay_toggled) callbacks_.overlay_toggled(on);
    });
    presets_ = menu_->addMenu("Preset");
    preset_group_ = new QActionGroup(presets_);
    preset_group_->setExclusive(true);
    set_presets(presets, current_preset);
    QObject::connect(preset_group_, &QActionGroup::triggered, menu_.get(), [this](QAction* a) {
        if (callbacks_.preset_chosen) callbacks_.preset_chosen(a->data().toString().toStdString());
    });
    QObject::connect(menu_->addAction("Tune…"), &QAction::triggered, menu_.get(), [this] {
        if (callbacks_.tune) callbacks_.tune();
    });
    add_common();
    set_status(status);
}

TrayMenu::TrayMenu(TrayCallbacks callbacks, const std::string& status)
    : callbacks_(std::move(callbacks)), menu_(std::make_unique<QMenu>()), tray_(std::make_unique<QSystemTrayIcon>()) {
    add_common();
    set_status(status);
}

void TrayMenu::set_status(const std::string& status) {
    if (status.empty()) {
        delete status_;
        delete status_separator_;
        status_ = status_separator_ = nullptr;
        tray_->setToolTip("umf provider");
        return;
    }
    const QString text = QString::fromStdString(status);
    if (!status_) {
        // A line to read, not to click, above everything else.
        QAction* first = menu_->actions().value(0);
        status_ = new QAction(text, menu_.get());
        status_->setEnabled(false);
        menu_->insertAction(first, status_);
        status_separator_ = menu_->insertSeparator(first);
    }
    status_->setText(text);
    tray_->setToolTip("umf provider: " + text);
}

void TrayMenu::add_common() {
    QObject::connect(menu_->addAction("Pairing QR code…"), &QAction::triggered, menu_.get(), [this] {
        if (callbacks_.pairing_qr) callbacks_.pairing_qr();
    });
    if (callbacks_.start_at_login) {
        start_at_login_ = menu_->addAction("Start at login");
        start_at_login_->setCheckable(true);
        QObject::connect(start_at_login_, &QAction::toggled, menu_.get(),
                         [this](bool on) { callbacks_.start_at_login(on); });
    }
    menu_->addSeparator();
    QObject::connect(menu_->addAction("Quit"), &QAction::triggered, menu_.get(), [this] {
        if (callbacks_.quit) callbacks_.quit();
    });
    // The installed icon (packaging/icons) where the theme has it, else the same drawn here.
    tray_->setIcon(QIcon::fromTheme("umf-provider", field_icon()));
    tray_->setToolTip("umf provider");
    tray_->setContextMenu(menu_.get());
}

// The icon goes before the menu it points to.
TrayMenu::~TrayMenu() { tray_.reset(); }

bool TrayMenu::available() { return QSystemTrayIcon::isSystemTrayAvailable(); }

void TrayMenu::show() { tray_->show(); }

void TrayMenu::set_presets(const std::vector<std::string>& presets, const std::string& current_preset) {
    if (!preset_group_) return;
    for (QAction* a : preset_group_->actions()) {
        preset_group_->removeAction(a);
        presets_->removeAction(a);
        delete a;
    }
    for (const auto& name : presets) {
        QAction* a = presets_->addAction(QString::fromStdString(name));
        a->setCheckable(true);
        a->setData(QString::fromStdString(name));
        a->setChecked(name == current_preset);
        preset_group_->addAction(a);
    }
}

void TrayMenu::set_overlay_on(bool on) {
    if (!overlay_) return;
    const QSignalBlocker quiet(overlay_);
    overlay_->setChecked(on);
}

void TrayMenu::set_start_at_login(bool on) {
    if (!start_at_login_) return;
    const QSignalBlocker quiet(start_at_login_);
    start_at_login_->setChecked(on);
}

}  // namespace umf::provider
