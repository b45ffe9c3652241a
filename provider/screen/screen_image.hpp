// The screen as the provider shows it, as an image: the board window and the
// field mixed in. `umf-provider compose` writes it, tests photograph it with
// the camera simulator, and the headless provider serves points on it; the
// field's pixels come from overlay/field_mix.hpp, the same as the overlay's.
// Everything here paints text, so a QGuiApplication must exist
// (gui_application.hpp).
#pragma once

#include <QImage>
#include <QSize>
#include <string>
#include <vector>

#include "provider/board/board.hpp"
#include "provider/screen/screen_field.hpp"

namespace umf::provider {

// The largest screen side accepted, as for the detector's images.
inline constexpr int kMaxScreenSide = 16384;

// The board window as shown full screen (Format_RGB32): a dark background,
// the title bar with the board's title, and each item's tile (tiles[i] is
// items[i]'s, as layout_board gives them) as a light rounded card, bluish for
// URLs and warm for files, with the item's title as large as fits (wrapped,
// elided when even the smallest size does not fit), the file name or the
// URL's host below it, and the thumbnail scaled to fit under them. A
// thumbnail that cannot be read (missing, broken, larger than 8192 pixels a
// side) is drawn as a plain placeholder. Throws std::invalid_argument for a
// screen size outside 1..kMaxScreenSide or tiles.size() != items.size(), and
// std::logic_error without a QGuiApplication.
QImage paint_board(const Board& board, const std::vector<PixelRect>& tiles, QSize screen);

// The screen as shown (Format_RGB888): `content` (which must have the
// screen's size; any format, its alpha dropped) or black, the board window
// over all of it when there is a board (laid out by layout_board), blurred
// under the field at `blur` (a preset's, 0..1; blur_under_field), then the
// field mixed in at `opacity` with `palette` (empty: the field's own). With
// blur 0 the pixels are exactly overlay::mix_field's over the content.
// Throws std::invalid_argument for a content or ScreenField of another size
// than the screen, a blur outside 0..1, and what paint_board and
// overlay::mix_field throw.
QImage compose_screen(const QImage* content, const Board* board, QSize screen, const ScreenField& field,
                      double opacity, const std::vector<std::string>& palette, double blur = 0.0);

// `image` with the pixels under the field blurred at `strength` (0..1) by
// overlay::blur_under_field, in place; the board window does this once to
// its board, compose to every screen. Format_RGB888 and Format_RGB32 are
// blurred as they are, any other format is converted to Format_RGB32 first.
// Strength 0 leaves the image untouched. Throws std::invalid_argument for a
// strength outside 0..1 or a field placed for another screen size.
void blur_under_field(QImage& image, const ScreenField& field, double strength);

}  // namespace umf::provider
