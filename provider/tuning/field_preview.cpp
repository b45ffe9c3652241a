#include "provider/tuning/field_preview.hpp"

#include <QGuiApplication>
#include <QPainter>
#include <QPainterPath>
#include <QScreen>
#include <QTimer>
#include <cmath>

#include "provider/common/install_paths.hpp"
#include "shared/field/default_field.hpp"
#include "shared/field/field_io.hpp"
#include "shared/overlay/background_blur.hpp"
#include "shared/overlay/field_mix.hpp"
#include "shared/overlay/placement.hpp"
#include "shared/overlay/pulse.hpp"

namespace umf::provider {

namespace {

// 30 frames a second: smooth for the slowest pulse (0.5 s), light on a
// machine that also runs the overlay.
constexpr int kFrameMs = 33;

bool single_colour(const QImage& image) {
    if (image.isNull()) return true;
    const QRgb first = image.pixel(0, 0);
    for (int y = 0; y < image.height(); y += 7)
        for (int x = 0; x < image.width(); x += 7)
            if (image.pixel(x, y) != first) return false;
    return true;
}

// The field on the preview: centred as on the screen, its module scaled
// with the screen, so it covers the same share of both.
overlay::FieldPlacement preview_placement(const Field& field, QSize size, double screen_width, double module_px) {
    return overlay::centred_placement(field.width, field.height, size.width(), size.height(),
                                      module_px * size.width() / screen_width);
}

}  // namespace

QImage synthetic_screen(QSize size) {
    QImage img(size, QImage::Format_RGB32);
    QPainter p(&img);
    QLinearGradient sky(0, 0, size.width(), size.height());
    sky.setColorAt(0, QColor(0x2b, 0x4a, 0x6f));
    sky.setColorAt(1, QColor(0x8a, 0x6d, 0x9e));
    p.fillRect(img.rect(), sky);
    const QRect window(size.width() / 8, size.height() / 8, size.width() * 5 / 8, size.height() * 5 / 8);
    p.fillRect(window, QColor(0xf4, 0xf1, 0xea));
    p.fillRect(QRect(window.topLeft(), QSize(window.width(), size.height() / 24)), QColor(0x3c, 0x3f, 0x44));
    const int line = std::max(2, size.height() / 40);
    for (int y = window.top() + size.height() / 12; y + line < window.bottom() - line; y += line * 2)
        p.fillRect(QRect(window.left() + line * 2, y, (window.width() - line * 4) * (3 + (y / line) % 3) / 5, line),
                   QColor(0x33, 0x33, 0x33));
    p.fillRect(QRect(size.width() * 11 / 16, size.height() / 3, size.width() / 4, size.height() / 2),
               QColor(0xd9, 0x8c, 0x3a));
    return img;
}

QImage grab_screen_or_synthetic() {
    if (QScreen* screen = QGuiApplication::primaryScreen()) {
        QImage shot = screen->grabWindow(0).toImage();
        if (!single_colour(shot)) return shot;
    }
    return synthetic_screen(QSize(1920, 1080));
}

FieldPreview::FieldPreview(const QImage& screen, QSize size, QWidget* parent)
    : QLabel(parent), size_(size), timer_(new QTimer(this)) {
    setFixedSize(size_);
    try {
        const DefaultField choice = default_field_for_screen(1920, 1080);
        field_ = load_field((shipped_fields_dir() / choice.file).string());
    } catch (const std::exception& e) {
        // Without the shipped field the window still edits presets.
        setText(QString::fromStdString(std::string("no preview: ") + e.what()));
        setWordWrap(true);
    }
    clock_.start();
    set_screen(screen);
    QObject::connect(timer_, &QTimer::timeout, this, [this] { tick(); });
    timer_->start(kFrameMs);
}

void FieldPreview::set_preset(const overlay::Preset& preset) {
    const bool blur_changed = preset.blur != preset_.blur || preset.module_px != preset_.module_px;
    preset_ = preset;
    if (blur_changed) blur_sample();
    tick();
}

void FieldPreview::set_screen(const QImage& screen) {
    const QImage source = screen.isNull() ? synthetic_screen(QSize(1920, 1080)) : screen;
    screen_width_ = source.width();
    sample_ = source.scaled(size_, Qt::IgnoreAspectRatio, Qt::SmoothTransformation)
                  .convertToFormat(QImage::Format_RGB32);
    blur_sample();
    tick();
}

void FieldPreview::blur_sample() {
    // The screen's own blur at the preview's module size: the sample is the
    // screen scaled down, so the blur's reach in modules, which is what the
    // strength sets, is the same in both. Once per change, not per frame.
    blurred_ = sample_;
    if (!field_ || !(preset_.blur > 0.0)) return;
    const auto placement = preview_placement(*field_, size_, screen_width_, preset_.module_px);
    const overlay::PixelBuffer buffer{blurred_.bits(), blurred_.width(), blurred_.height(), blurred_.bytesPerLine(),
                                      4, true};
    // A half-edited preset (a module size of 0, say) is previewed unblurred.
    if (!overlay::blur_under_field(buffer, field_->width, field_->height, placement, std::min(preset_.blur, 1.0)))
        blurred_ = sample_;
}

QImage FieldPreview::frame(double t_s) const {
    QImage background = sample_;
    if (!field_) return background;
    // The blur lies under the field only, so where a focus region hides the
    // field the screen shows sharp.
    QImage mixed = blurred_;
    const auto placement = preview_placement(*field_, size_, screen_width_, preset_.module_px);
    const double module_px = placement.module_px;
    overlay::PixelBuffer buffer{mixed.bits(), mixed.width(), mixed.height(), mixed.bytesPerLine(), 4, true};
    const double opacity = overlay::opacity_at(preset_, t_s);
    try {
        overlay::mix_field(buffer, *field_, placement, opacity, preset_.palette);
    } catch (const std::invalid_argument&) {
        // A palette half-edited (one colour, say): the field's own until it is whole.
        overlay::mix_field(buffer, *field_, placement, opacity);
    }
    if (preset_.region == overlay::Region::full) return mixed;
    QPainter p(&background);
    QPainterPath circle;
    const double r = preset_.focus_radius_modules * module_px;
    circle.addEllipse(QPointF(size_.width() / 2.0, size_.height() / 2.0), r, r);
    p.setClipPath(circle);
    p.drawImage(0, 0, mixed);
    return background;
}

void FieldPreview::tick() {
    if (!field_) return;
    setPixmap(QPixmap::fromImage(frame(clock_.elapsed() / 1000.0)));
}

}  // namespace umf::provider
