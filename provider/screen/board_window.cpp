#include "provider/screen/board_window.hpp"

#include <QPainter>
#include <QScreen>
#include <cmath>

#include "provider/screen/screen_image.hpp"
#include "shared/overlay/field_mix.hpp"
#include "shared/overlay/pulse.hpp"

namespace umf::provider {

QImage field_layer(const ScreenField& field, const std::vector<std::string>& palette) {
    QImage layer(field.screen_width, field.screen_height, QImage::Format_ARGB32_Premultiplied);
    layer.fill(Qt::transparent);
    const auto& p = field.placement;
    // The pixels whose centres lie on the field: origin <= x + 0.5 < origin + width * module.
    auto first = [](double origin) { return static_cast<int>(std::ceil(origin - 0.5)); };
    const int x0 = std::max(0, first(p.origin_x)), y0 = std::max(0, first(p.origin_y));
    const int x1 = std::min(layer.width(), first(p.origin_x + field.field.width * p.module_px));
    const int y1 = std::min(layer.height(), first(p.origin_y + field.field.height * p.module_px));
    for (int y = y0; y < y1; ++y) {
        auto* row = reinterpret_cast<QRgb*>(layer.scanLine(y));
        for (int x = x0; x < x1; ++x) row[x] = qRgba(0, 0, 0, 255);
    }
    // Opaque black where the field is, then the module colours at full
    // opacity: alpha is left as it is by mix_field.
    overlay::PixelBuffer buffer{layer.bits(), layer.width(), layer.height(), layer.bytesPerLine(), 4, true};
    overlay::mix_field(buffer, field.field, field.placement, 1.0, palette);
    return layer;
}

void paint_board_frame(QPainter& painter, const QImage& board, const QImage& layer, double opacity) {
    painter.setCompositionMode(QPainter::CompositionMode_Source);
    painter.drawImage(0, 0, board);
    painter.setCompositionMode(QPainter::CompositionMode_SourceOver);
    painter.setOpacity(std::clamp(opacity, 0.0, 1.0));
    painter.drawImage(0, 0, layer);
    painter.setOpacity(1.0);
}

QImage board_under_field(QImage board, const ScreenField& field, const overlay::Preset& preset) {
    blur_under_field(board, field, preset.blur);
    return board;
}

BoardWindow::BoardWindow(QImage board, const ScreenField& field, const overlay::Preset& preset, QScreen* screen)
    : BoardWindow(board_under_field(std::move(board), field, preset), field_layer(field, preset.palette), preset,
                  screen) {}

BoardWindow::BoardWindow(QImage board, QImage layer, overlay::Preset preset, QScreen* screen)
    : board_(std::move(board)), layer_(std::move(layer)), preset_(std::move(preset)) {
    if (screen) {
        setScreen(screen);
        // Without a window manager a full-screen request is not honoured; the
        // window covers the screen by its own geometry as well.
        setGeometry(screen->geometry());
    }
    setFlags(Qt::Window | Qt::FramelessWindowHint);
    setTitle("umf board");
    clock_.start();
    // 30 checks a second; a repaint only when the opacity moved by a level
    // a screen could show.
    timer_.setInterval(33);
    QObject::connect(&timer_, &QTimer::timeout, this, [this] { tick(); });
    timer_.start();
}

void BoardWindow::show_field(QImage board, const ScreenField& field) {
    board_ = board_under_field(std::move(board), field, preset_);
    layer_ = field_layer(field, preset_.palette);
    painted_opacity_ = -1.0;
    update();
}

double BoardWindow::opacity_now() const {
    // A board is there to be pointed at: its field does not wait for a requester.
    return overlay::opacity_at(preset_, static_cast<double>(clock_.elapsed()) / 1000.0);
}

void BoardWindow::tick() {
    if (std::abs(opacity_now() - painted_opacity_) >= 0.5 / 255.0) update();
}

void BoardWindow::paintEvent(QPaintEvent*) {
    QPainter painter(this);
    const double opacity = opacity_now();
    // The images are the screen's physical pixels; the window's coordinates
    // are logical on a scaled screen.
    painter.scale(1.0 / devicePixelRatio(), 1.0 / devicePixelRatio());
    paint_board_frame(painter, board_, layer_, opacity);
    painted_opacity_ = opacity;
}

}  // namespace umf::provider
