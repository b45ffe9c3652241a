// PNG output: an indexed image whose palette is the field's palette, so a
// binary field is stored at one bit per pixel before compression.
#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "shared/field/render_internal.hpp"

namespace umf::render_detail {

namespace {

// Glyph cells are 6 font pixels wide (5 + 1 spacing); the band around the 7
// rows of a glyph leaves 6 font pixels above and below.
constexpr int kCellWidth = 6;
constexpr int kGlyphHeight = 7;
constexpr int kBandMargin = 6;

struct PixelCaption {
    std::string text;  // printable ASCII, already cut to fit
    int scale = 0;     // image pixels per font pixel
    int band = 0;      // image rows added for the caption
};

long long text_width(std::size_t chars, int scale) { return (kCellWidth * static_cast<long long>(chars) - 1) * scale; }

// Aims for the cap height of the vector formats (0.72 of a module) and shrinks
// the font, then the text, when the caption is wider than the image.
PixelCaption fit_caption(const Style& style, double module_px, int image_width) {
    PixelCaption caption;
    caption.text = to_printable_ascii(style.caption);
    if (caption.text.empty()) return {};
    int scale = std::max(1, static_cast<int>(std::lround(module_px * 0.72 / kGlyphHeight)));
    double usable = 0.9 * image_width;
    while (scale > 1 && static_cast<double>(text_width(caption.text.size(), scale)) > usable) --scale;
    auto fits = static_cast<std::size_t>((image_width + 1) / kCellWidth);
    if (caption.text.size() > fits) caption.text.resize(fits);
    if (caption.text.empty()) return {};
    caption.scale = scale;
    caption.band = (2 * kBandMargin + kGlyphHeight) * scale;
    return caption;
}

// For each of `pixels` pixels, the module it falls in. Module k covers pixels
// [round(k * scale), round((k + 1) * scale)), which keeps the total size exact
// for fractional scales at the price of modules differing by one pixel.
std::vector<int> module_of_pixel(int modules, double scale, int pixels) {
    std::vector<int> out(static_cast<std::size_t>(pixels));
    int module = 0;
    for (int p = 0; p < pixels; ++p) {
        while (module + 1 < modules && p >= std::lround((module + 1) * scale)) ++module;
        out[static_cast<std::size_t>(p)] = module;
    }
    return out;
}

void draw_caption(std::vector<std::uint8_t>& pixels, int width, int top, const PixelCaption& caption,
                  std::uint8_t ink) {
    int s = caption.scale;
    long long left = (width - text_width(caption.text.size(), s)) / 2;
    int y0 = top + kBandMargin * s;
    for (std::size_t k = 0; k < caption.text.size(); ++k) {
        const auto& rows = glyph_rows(caption.text[k]);
        for (int gy = 0; gy < kGlyphHeight; ++gy) {
            for (int gx = 0; gx < 5; ++gx) {
                if (!(rows[static_cast<std::size_t>(gy)] & (0x10 >> gx))) continue;
                long long x0 = left + (static_cast<long long>(k) * kCellWidth + gx) * s;
                for (int y = y0 + gy * s; y < y0 + (gy + 1) * s; ++y)
                    for (long long x = std::max(0LL, x0); x < std::min<long long>(width, x0 + s); ++x)
                        pixels[static_cast<std::size_t>(y) * width + static_cast<std::size_t>(x)] = ink;
            }
        }
    }
}

}  // namespace

std::string render_png(const Field& field, const Style& style, const RenderOptions& options) {
    bool physical = options.module_mm > 0;
    double scale = physical ? options.module_mm / 25.4 * options.dpi : module_units(options);
    if (scale < 1)
        throw std::invalid_argument("module_mm " + format_number(options.module_mm, 6) + " at " +
                                    format_number(options.dpi, 2) + " dpi is " + format_number(scale, 2) +
                                    " pixels per module; a PNG needs at least 1");
    double width = std::round(style.cols * scale);
    double field_height = std::round(style.rows * scale);
    auto too_large = [&](double w, double h) {
        return std::invalid_argument(
            "a " + std::to_string(field.width) + " x " + std::to_string(field.height) + " field with a quiet zone of " +
            std::to_string(style.quiet) + " at " + format_number(scale, 2) + " pixels per module makes a " +
            format_number(w, 0) + " x " + format_number(h, 0) + " pixel PNG; the limit is " +
            std::to_string(kMaxImageSide) + " pixels a side and " + std::to_string(kMaxImagePixels) + " pixels in all");
    };
    if (width > kMaxImageSide || field_height > kMaxImageSide) throw too_large(width, field_height);
    int w = static_cast<int>(width);
    int field_h = static_cast<int>(field_height);
    PixelCaption caption = fit_caption(style, scale, w);
    long long h = field_h + static_cast<long long>(caption.band);
    if (h > kMaxImageSide || static_cast<long long>(w) * h > kMaxImagePixels)
        throw too_large(w, static_cast<double>(h));

    std::vector<int> col_of = module_of_pixel(style.cols, scale, w);
    std::vector<int> row_of = module_of_pixel(style.rows, scale, field_h);
    std::vector<std::uint8_t> pixels(static_cast<std::size_t>(w) * static_cast<std::size_t>(h), style.light);
    for (int y = 0; y < field_h; ++y) {
        int row = row_of[static_cast<std::size_t>(y)] - style.quiet;
        if (row < 0 || row >= field.height) continue;
        std::uint8_t* line = pixels.data() + static_cast<std::size_t>(y) * w;
        if (y > 0 && row_of[static_cast<std::size_t>(y)] == row_of[static_cast<std::size_t>(y) - 1]) {
            std::copy(line - w, line, line);
            continue;
        }
        for (int x = 0; x < w; ++x) {
            int col = col_of[static_cast<std::size_t>(x)] - style.quiet;
            if (col >= 0 && col < field.width) line[x] = field.at(row, col);
        }
    }
    if (caption.band > 0) draw_caption(pixels, w, field_h, caption, style.dark);
    return encode_png_indexed(w, static_cast<int>(h), style.palette, pixels, physical ? options.dpi : 0);
}

}  // namespace umf::render_detail
