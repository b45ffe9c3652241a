// Pieces shared by the PNG, SVG and PDF renderers; not part of the public API.
#pragma once

#include <array>
#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

#include "shared/field/field.hpp"
#include "shared/field/png_writer.hpp"
#include "shared/field/render.hpp"

namespace umf::render_detail {

// What every format needs, worked out once from a validated field and options.
struct Style {
    std::vector<Rgb> palette;  // one colour per module value
    std::uint8_t light = 0;    // palette index of the quiet zone and caption band
    std::uint8_t dark = 0;     // palette index of the caption text
    int quiet = 0;             // quiet zone in modules
    int cols = 0;              // width in modules, quiet zone included
    int rows = 0;              // height in modules, quiet zone included (caption band excluded)
    std::u32string caption;    // valid code points, control characters turned into spaces
};

// Throws std::invalid_argument for an invalid field or options that no format accepts.
Style make_style(const Field& field, const RenderOptions& options);

// Module size in the vector formats' unit when no mm size is set (px for SVG, pt for PDF).
double module_units(const RenderOptions& options);

struct Run {
    int row = 0;  // field row, without the quiet zone
    int col = 0;  // first field column of the run
    int length = 0;
    std::uint8_t value = 0;
};

// Maximal horizontal runs of equal modules, row by row.
std::vector<Run> horizontal_runs(const Field& field);

// "#rrggbb", lower case.
std::string hex_colour(const Rgb& colour);

// Fixed-point decimal with trailing zeros removed ("12.5", "3", "-0.25").
// Unlike printf it ignores the C locale, which GUI toolkits often set to one
// with a decimal comma, producing broken SVG and PDF.
std::string format_number(double value, int decimals = 4);

// Lossy on purpose: a caption is decoration, so bad bytes become U+FFFD
// rather than an error, and control characters (which XML forbids and no font
// draws) become spaces.
std::u32string decode_text(std::string_view utf8);

std::string to_utf8(std::u32string_view text);

// Printable ASCII kept, everything else replaced by '?': what the PDF
// standard fonts and the PNG pixel font can draw.
std::string to_printable_ascii(std::u32string_view text);

// Advance width of a character in Helvetica, in em. Non-ASCII characters get
// the width of a digit, a fair average for the fonts viewers substitute.
double helvetica_width(char32_t c);

// Where the vector formats put the caption, in module units from the top left.
struct CaptionBox {
    double font_size = 0;  // em in module units
    double band = 0;       // height of the band added below the quiet zone
    double baseline = 0;   // y of the text baseline
    double left = 0;       // x where the text starts, for centred text
    double width = 0;      // estimated advance width of the whole text
};

// All zeros when there is no caption.
CaptionBox vector_caption_box(const Style& style);

// Rows of a 5x7 pixel glyph, top first; bit 4 is the leftmost column. Printable
// ASCII only; anything else gets the '?' glyph.
const std::array<std::uint8_t, 7>& glyph_rows(char c);

std::string render_png(const Field& field, const Style& style, const RenderOptions& options);
std::string render_svg(const Field& field, const Style& style, const RenderOptions& options);
std::string render_pdf(const Field& field, const Style& style, const RenderOptions& options);

}  // namespace umf::render_detail
