// Turns a marker field into an image file: PNG for screens, SVG and PDF for
// print and further editing.
//
// Layout, in module units: the field's module (row i, column j) covers
// x in [q + j, q + j + 1], y in [q + i, q + i + 1], where q is the quiet zone;
// row 0 is at the top. The quiet zone is filled with the lightest palette
// colour (highest luma). An optional caption sits in a band of the same
// colour below the quiet zone, in the darkest palette colour, centred.
//
// Sizes: module_mm, when set, wins: SVG gets width/height in mm, PDF a page
// of module_mm / 25.4 * 72 points per module, PNG module_mm / 25.4 * dpi
// pixels per module (module edges are rounded to whole pixels, so modules may
// differ by one pixel while the total size stays exact) plus a pHYs chunk
// recording dpi. Otherwise module_px is used: pixels per module for PNG and
// SVG, points per module for PDF; 0 means 10.
//
// Captions: SVG keeps any Unicode text (the viewer's sans-serif font draws
// it); PDF uses the standard Helvetica font and replaces every non-ASCII
// character by '?'; PNG draws it with a built-in 5x7 pixel font for printable
// ASCII (others become '?'), scaled with the module size, shrunk to fit and
// cut off at the image width if even the smallest size does not fit.
#pragma once

#include <string>

#include "shared/field/field.hpp"

namespace umf {

struct RenderOptions {
    int module_px = 0;     // pixels per module (PNG; SVG/PDF use it as their unit when no mm size is set)
    double module_mm = 0;  // physical module size in millimetres (for printing); for PNG combined with dpi
    double dpi = 300;      // only used to turn module_mm into pixels for PNG
    int quiet_zone = 0;    // margin in modules around the field, drawn in the lightest palette colour
    std::string caption;   // optional text under the field (empty = none)
};

enum class ImageFormat { png, svg, pdf };

// Limits on PNG output, so that a typo in the options cannot ask for gigabytes.
inline constexpr int kMaxImageSide = 16384;
inline constexpr long long kMaxImagePixels = 256'000'000;

const char* to_string(ImageFormat format);

// The format named by a file name's extension (.png/.svg/.pdf, any case).
// Throws std::invalid_argument for anything else.
ImageFormat image_format_for_path(const std::string& path);

// The encoded file's bytes. Throws std::invalid_argument for an invalid field
// or bad options (negative sizes, non-positive dpi, a module under one pixel,
// or a PNG over kMaxImageSide pixels a side or kMaxImagePixels in all).
std::string render_field(const Field& field, ImageFormat format, const RenderOptions& options);

}  // namespace umf
