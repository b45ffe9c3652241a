// The board shown for real: a frameless full-screen window of the board's
// tiles with the field mixed in at the preset's pulsing opacity. The board and
// the field are painted once; each frame only blends the two, which QPainter
// does in SIMD, and the window repaints only when the opacity has moved.
#pragma once

#include <QElapsedTimer>
#include <QImage>
#include <QRasterWindow>
#include <QTimer>

#include "provider/screen/screen_field.hpp"
#include "shared/overlay/preset.hpp"

class QPainter;
class QScreen;

namespace umf::provider {

// The field as a layer over the screen (Format_ARGB32_Premultiplied): the
// module colours, opaque on the pixels whose centres lie on the field (the
// pixels overlay::mix_field changes), transparent elsewhere. Drawn at opacity
// a over the board it gives compose_screen's pixels to within rounding.
QImage field_layer(const ScreenField& field, const std::vector<std::string>& palette);

// One frame: the board, then the layer at `opacity`.
void paint_board_frame(QPainter& painter, const QImage& board, const QImage& layer, double opacity);

// The board as the window shows it under the field: blurred under the
// field at the preset's `blur` (screen_image.hpp's blur_under_field), once,
// so that each frame is still only a blend. Throws std::invalid_argument for
// a board of another size than the field's screen.
QImage board_under_field(QImage board, const ScreenField& field, const overlay::Preset& preset);

class BoardWindow : public QRasterWindow {
public:
    // `board` as it is shown, `layer` from field_layer: no blur is applied.
    BoardWindow(QImage board, QImage layer, overlay::Preset preset, QScreen* screen);
    // The board painted (paint_board), the field it shows and the preset:
    // board_under_field and field_layer, so the preset's blur and palette
    // both apply. Throws what board_under_field throws.
    BoardWindow(QImage board, const ScreenField& field, const overlay::Preset& preset, QScreen* screen);
    // Another field under the same preset (a new seed): `board` painted
    // without a field, as for the constructor above.
    void show_field(QImage board, const ScreenField& field);

protected:
    void paintEvent(QPaintEvent* event) override;

private:
    double opacity_now() const;
    void tick();

    QImage board_;
    QImage layer_;
    overlay::Preset preset_;
    QElapsedTimer clock_;
    QTimer timer_;
    double painted_opacity_ = -1.0;
};

}  // namespace umf::provider
