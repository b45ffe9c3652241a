#include "provider/screen/screen_image.hpp"

#include <QFont>
#include <QFontMetrics>
#include <QGuiApplication>
#include <QImageReader>
#include <QPainter>
#include <QPainterPath>
#include <QString>
#include <QStringList>
#include <QTextLayout>
#include <QUrl>
#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "shared/overlay/background_blur.hpp"
#include "shared/overlay/field_mix.hpp"

namespace umf::provider {

namespace {

// Colours chosen for contrast at a glance from across a room: light cards on
// a dark neutral background, near-black text.
const QColor kBackground(0x20, 0x23, 0x28);
const QColor kTitleBar(0x2e, 0x33, 0x3b);
const QColor kTitleText(0xf2, 0xf4, 0xf7);
const QColor kFileCard(0xf4, 0xee, 0xdc);
const QColor kUrlCard(0xdc, 0xe9, 0xf6);
const QColor kCardText(0x1c, 0x1f, 0x24);
const QColor kCardSubtext(0x4e, 0x56, 0x60);

constexpr int kMinTitlePx = 10;
constexpr int kMaxThumbnailSide = 8192;

void check_screen(QSize screen, const char* who) {
    if (screen.width() < 1 || screen.height() < 1 || screen.width() > kMaxScreenSide ||
        screen.height() > kMaxScreenSide)
        throw std::invalid_argument(std::string(who) + ": screen size " + std::to_string(screen.width()) + " x " +
                                    std::to_string(screen.height()) + " is outside 1.." +
                                    std::to_string(kMaxScreenSide));
}

QString qt_string(const std::string& utf8) { return QString::fromUtf8(utf8.data(), static_cast<qsizetype>(utf8.size())); }

// `text` broken into lines of at most `width` pixels; when more than
// `max_lines` are needed, the last one kept ends in an ellipsis.
QStringList wrapped_lines(const QString& text, const QFont& font, int width, int max_lines, bool& fits) {
    QTextLayout layout(text, font);
    QTextOption option;
    option.setWrapMode(QTextOption::WrapAtWordBoundaryOrAnywhere);
    layout.setTextOption(option);
    QStringList lines;
    layout.beginLayout();
    int last_start = 0;
    fits = true;
    for (;;) {
        QTextLine line = layout.createLine();
        if (!line.isValid()) break;
        line.setLineWidth(width);
        if (lines.size() == max_lines) {
            fits = false;
            break;
        }
        last_start = line.textStart();
        lines.append(text.mid(line.textStart(), line.textLength()).trimmed());
    }
    layout.endLayout();
    if (!fits && !lines.isEmpty())
        lines.back() = QFontMetrics(font).elidedText(text.mid(last_start).simplified(), Qt::ElideRight, width);
    return lines;
}

// What the tile names under its title: the file's name or the URL's host.
QString subtitle(const BoardItem& item) {
    if (item.file) return qt_string(item.file->filename().string());
    if (item.url) {
        const QUrl url(qt_string(*item.url));
        if (url.isValid() && !url.host().isEmpty()) return url.host();
        return qt_string(*item.url);
    }
    return {};
}

// The thumbnail decoded at the size it is drawn (so a large photo costs no
// more than a small one), or a null image when it cannot be read.
QImage load_thumbnail(const std::filesystem::path& file, QSize box) {
    QImageReader reader(qt_string(file.string()));
    reader.setAutoTransform(true);
    const QSize size = reader.size();
    if (!size.isValid() || size.isEmpty() || size.width() > kMaxThumbnailSide || size.height() > kMaxThumbnailSide)
        return {};
    reader.setScaledSize(size.scaled(box, Qt::KeepAspectRatio).expandedTo(QSize(1, 1)));
    return reader.read();
}

void paint_title_bar(QPainter& p, const Board& board, int width, int height) {
    if (height <= 0) return;
    p.fillRect(0, 0, width, height, kTitleBar);
    QFont font;
    font.setPixelSize(std::max(kMinTitlePx, height / 2));
    font.setBold(true);
    p.setFont(font);
    p.setPen(kTitleText);
    const int pad = std::max(8, height / 3);
    const QRect area(pad, 0, std::max(1, width - 2 * pad), height);
    p.drawText(area, Qt::AlignLeft | Qt::AlignVCenter,
               QFontMetrics(font).elidedText(qt_string(board.title), Qt::ElideRight, area.width()));
}

void paint_tile(QPainter& p, const BoardItem& item, const PixelRect& tile) {
    if (tile.width <= 0 || tile.height <= 0) return;
    const QRectF card(tile.x, tile.y, tile.width, tile.height);
    const int side = std::min(tile.width, tile.height);
    const double radius = std::max(2.0, side * 0.06);
    QPainterPath path;
    path.addRoundedRect(card, radius, radius);
    p.fillPath(path, item.url ? kUrlCard : kFileCard);

    const int pad = std::max(4, static_cast<int>(std::lround(side * 0.06)));
    const QRect inner = QRect(tile.x, tile.y, tile.width, tile.height).adjusted(pad, pad, -pad, -pad);
    if (inner.width() < 4 || inner.height() < 4) return;

    // The title as large as fits in its share of the card: the largest size
    // at which it wraps into the space, elided at the smallest.
    const bool thumbnail = item.thumbnail.has_value();
    const int title_space = static_cast<int>(inner.height() * (thumbnail ? 0.32 : 0.6));
    QFont font;
    font.setBold(true);
    const int largest = std::clamp(static_cast<int>(std::min(inner.height() * 0.16, inner.width() * 0.1)),
                                   kMinTitlePx, 96);
    QStringList lines;
    int size = largest;
    for (;; size = std::max(kMinTitlePx, size * 9 / 10)) {
        font.setPixelSize(size);
        const int line_height = QFontMetrics(font).lineSpacing();
        const int max_lines = std::max(1, title_space / std::max(1, line_height));
        bool fits = false;
        lines = wrapped_lines(qt_string(item.title), font, inner.width(), max_lines, fits);
        if (fits || size == kMinTitlePx) break;
    }
    const QFontMetrics title_metrics(font);
    p.setFont(font);
    p.setPen(kCardText);
    int y = inner.top();
    for (const QString& line : lines) {
        p.drawText(QRect(inner.left(), y, inner.width(), title_metrics.lineSpacing()), Qt::AlignLeft | Qt::AlignTop,
                   line);
        y += title_metrics.lineSpacing();
    }

    QFont small;
    small.setPixelSize(std::max(kMinTitlePx, size * 11 / 20));
    const QFontMetrics small_metrics(small);
    y += small_metrics.lineSpacing() / 4;
    if (y + small_metrics.lineSpacing() <= inner.bottom() + 1) {
        p.setFont(small);
        p.setPen(kCardSubtext);
        p.drawText(QRect(inner.left(), y, inner.width(), small_metrics.lineSpacing()), Qt::AlignLeft | Qt::AlignTop,
                   small_metrics.elidedText(subtitle(item), Qt::ElideMiddle, inner.width()));
        y += small_metrics.lineSpacing();
    }

    if (!thumbnail) return;
    const QRect box(inner.left(), y + pad / 2, inner.width(), inner.bottom() + 1 - (y + pad / 2));
    if (box.width() < 8 || box.height() < 8) return;
    const QImage image = load_thumbnail(*item.thumbnail, box.size());
    if (image.isNull()) {
        const QColor tone = (item.url ? kUrlCard : kFileCard).darker(118);
        p.fillRect(box, tone);
        p.setPen(QPen(tone.darker(125), 1));
        p.drawRect(box.adjusted(0, 0, -1, -1));
        return;
    }
    const QImage fitted = image.size().width() > box.width() || image.size().height() > box.height()
                              ? image.scaled(box.size(), Qt::KeepAspectRatio, Qt::SmoothTransformation)
                              : image;
    p.drawImage(QPoint(box.left() + (box.width() - fitted.width()) / 2, box.top() + (box.height() - fitted.height()) / 2),
                fitted);
}

}  // namespace

QImage paint_board(const Board& board, const std::vector<PixelRect>& tiles, QSize screen) {
    check_screen(screen, "paint_board");
    if (tiles.size() != board.items.size())
        throw std::invalid_argument("paint_board: " + std::to_string(tiles.size()) + " tiles for " +
                                    std::to_string(board.items.size()) + " items");
    if (!qobject_cast<QGuiApplication*>(QCoreApplication::instance()))
        throw std::logic_error("paint_board: painting text needs a QGuiApplication");
    QImage image(screen, QImage::Format_RGB32);
    if (image.isNull())
        throw std::runtime_error("paint_board: no memory for a " + std::to_string(screen.width()) + " x " +
                                 std::to_string(screen.height()) + " image");
    image.fill(kBackground);
    QPainter p(&image);
    p.setRenderHint(QPainter::Antialiasing);
    p.setRenderHint(QPainter::TextAntialiasing);
    p.setRenderHint(QPainter::SmoothPixmapTransform);
    paint_title_bar(p, board, screen.width(), board_title_height(board, screen.height()));
    for (std::size_t i = 0; i < tiles.size(); ++i) paint_tile(p, board.items[i], tiles[i]);
    p.end();
    return image;
}

void blur_under_field(QImage& image, const ScreenField& field, double strength) {
    if (!(strength >= 0.0 && strength <= 1.0))
        throw std::invalid_argument("blur_under_field: strength must be 0..1, not " + std::to_string(strength));
    if (image.width() != field.screen_width || image.height() != field.screen_height)
        throw std::invalid_argument("blur_under_field: the field is placed for a " +
                                    std::to_string(field.screen_width) + " x " + std::to_string(field.screen_height) +
                                    " screen, the image is " + std::to_string(image.width()) + " x " +
                                    std::to_string(image.height()));
    if (strength == 0.0 || image.isNull()) return;
    if (image.format() != QImage::Format_RGB888 && image.format() != QImage::Format_RGB32)
        image = image.convertToFormat(QImage::Format_RGB32);
    if (image.isNull()) throw std::runtime_error("blur_under_field: no memory for the image");
    // Format_RGB32 is 0xffRRGGBB in a 32-bit word: the padding byte is last
    // in memory on little-endian machines, where the blur leaves it alone.
    const bool four = image.format() == QImage::Format_RGB32;
    const overlay::PixelBuffer pixels{image.bits(), image.width(), image.height(), image.bytesPerLine(),
                                      four ? 4 : 3, four};
    if (!overlay::blur_under_field(pixels, field.field.width, field.field.height, field.placement, strength))
        throw std::invalid_argument("blur_under_field: the field's placement has no positive, finite module size");
}

QImage compose_screen(const QImage* content, const Board* board, QSize screen, const ScreenField& field,
                      double opacity, const std::vector<std::string>& palette, double blur) {
    check_screen(screen, "compose_screen");
    if (field.screen_width != screen.width() || field.screen_height != screen.height())
        throw std::invalid_argument("compose_screen: the field is placed for a " + std::to_string(field.screen_width) +
                                    " x " + std::to_string(field.screen_height) + " screen, not " +
                                    std::to_string(screen.width()) + " x " + std::to_string(screen.height()));
    if (!(blur >= 0.0 && blur <= 1.0))
        throw std::invalid_argument("compose_screen: blur must be 0..1, not " + std::to_string(blur));
    if (content && content->size() != screen)
        throw std::invalid_argument("compose_screen: the content is " + std::to_string(content->width()) + " x " +
                                    std::to_string(content->height()) + " pixels, the screen " +
                                    std::to_string(screen.width()) + " x " + std::to_string(screen.height()));
    QImage out;
    if (board) {
        // The board window is full screen: nothing of the content shows.
        out = paint_board(*board, layout_board(*board, screen.width(), screen.height()), screen)
                  .convertToFormat(QImage::Format_RGB888);
    } else if (content) {
        out = content->convertToFormat(QImage::Format_RGB888);
    } else {
        out = QImage(screen, QImage::Format_RGB888);
        out.fill(Qt::black);
    }
    if (out.isNull()) throw std::runtime_error("compose_screen: no memory for the screen image");
    // Before the field: the field's own edges must stay sharp, only what
    // competes with them is blurred.
    blur_under_field(out, field, blur);
    overlay::PixelBuffer pixels{out.bits(), out.width(), out.height(), out.bytesPerLine(), 3, false};
    overlay::mix_field(pixels, field.field, field.placement, opacity, palette);
    return out;
}

}  // namespace umf::provider
