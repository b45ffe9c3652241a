#include "shared/field/render.hpp"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <stdexcept>

#include "shared/field/render_internal.hpp"

namespace umf {

namespace render_detail {

namespace {

constexpr double kDefaultModulePx = 10;
// Ten metres per module is beyond any print job and keeps every coordinate
// well inside what format_number() can represent.
constexpr double kMaxModuleMm = 10000;

Rgb parse_hex_colour(const std::string& text) {
    // describe_invalid() has already checked the "#rrggbb" shape.
    auto channel = [&](std::size_t at) {
        return static_cast<std::uint8_t>(std::stoi(text.substr(at, 2), nullptr, 16));
    };
    return {channel(1), channel(3), channel(5)};
}

double luma(const Rgb& c) { return 0.299 * c[0] + 0.587 * c[1] + 0.114 * c[2]; }

}  // namespace

std::u32string decode_text(std::string_view text) {
    constexpr char32_t kReplacement = 0xFFFD;
    std::u32string out;
    std::size_t i = 0;
    while (i < text.size()) {
        auto lead = static_cast<unsigned char>(text[i]);
        std::size_t length = lead < 0x80             ? 1
                             : (lead & 0xE0) == 0xC0 ? 2
                             : (lead & 0xF0) == 0xE0 ? 3
                             : (lead & 0xF8) == 0xF0 ? 4
                                                     : 0;
        char32_t cp = length == 1 ? lead : length == 2 ? lead & 0x1F : length == 3 ? lead & 0x0F : lead & 0x07;
        bool ok = length > 0 && i + length <= text.size();
        for (std::size_t k = 1; ok && k < length; ++k) {
            auto next = static_cast<unsigned char>(text[i + k]);
            ok = (next & 0xC0) == 0x80;
            cp = cp << 6 | (next & 0x3F);
        }
        constexpr char32_t kShortest[] = {0, 0, 0x80, 0x800, 0x10000};
        ok = ok && cp >= kShortest[length] && cp <= 0x10FFFF && !(cp >= 0xD800 && cp <= 0xDFFF);
        if (!ok) {
            out.push_back(kReplacement);
            ++i;
            continue;
        }
        if (cp < 0x20 || (cp >= 0x7F && cp <= 0x9F))
            cp = U' ';
        else if (cp == 0xFFFE || cp == 0xFFFF)
            cp = kReplacement;
        out.push_back(cp);
        i += length;
    }
    return out;
}

namespace {

std::string show(double value) {
    if (std::isnan(value)) return "nan";
    if (std::isinf(value)) return value > 0 ? "inf" : "-inf";
    return std::abs(value) < 1e12 ? format_number(value, 6) : std::to_string(value);
}

void check_options(const RenderOptions& o) {
    if (o.module_px < 0)
        throw std::invalid_argument("module_px must not be negative, got " + std::to_string(o.module_px));
    if (!(o.module_mm >= 0 && o.module_mm <= kMaxModuleMm))
        throw std::invalid_argument("module_mm must be between 0 and " + show(kMaxModuleMm) + ", got " +
                                    show(o.module_mm));
    if (!(o.dpi > 0) || !std::isfinite(o.dpi)) throw std::invalid_argument("dpi must be positive, got " + show(o.dpi));
    if (o.quiet_zone < 0 || o.quiet_zone > kMaxFieldSide)
        throw std::invalid_argument("quiet_zone must be between 0 and " + std::to_string(kMaxFieldSide) +
                                    " modules, got " + std::to_string(o.quiet_zone));
}

}  // namespace

Style make_style(const Field& field, const RenderOptions& options) {
    if (std::string problem = describe_invalid(field); !problem.empty())
        throw std::invalid_argument("cannot render field '" + field.id + "': " + problem);
    check_options(options);
    Style style;
    for (const std::string& hex : field.palette.empty() ? grey_palette(field.colors) : field.palette)
        style.palette.push_back(parse_hex_colour(hex));
    for (std::size_t i = 1; i < style.palette.size(); ++i) {
        if (luma(style.palette[i]) > luma(style.palette[style.light])) style.light = static_cast<std::uint8_t>(i);
        if (luma(style.palette[i]) < luma(style.palette[style.dark])) style.dark = static_cast<std::uint8_t>(i);
    }
    style.quiet = options.quiet_zone;
    style.cols = field.width + 2 * options.quiet_zone;
    style.rows = field.height + 2 * options.quiet_zone;
    style.caption = decode_text(options.caption);
    return style;
}

double module_units(const RenderOptions& options) {
    return options.module_px > 0 ? options.module_px : kDefaultModulePx;
}

std::vector<Run> horizontal_runs(const Field& field) {
    std::vector<Run> runs;
    for (int row = 0; row < field.height; ++row) {
        for (int col = 0; col < field.width;) {
            int end = col + 1;
            while (end < field.width && field.at(row, end) == field.at(row, col)) ++end;
            runs.push_back({row, col, end - col, field.at(row, col)});
            col = end;
        }
    }
    return runs;
}

std::string hex_colour(const Rgb& colour) {
    constexpr char kDigits[] = "0123456789abcdef";
    std::string out = "#";
    for (std::uint8_t c : colour) {
        out.push_back(kDigits[c >> 4]);
        out.push_back(kDigits[c & 0xF]);
    }
    return out;
}

std::string format_number(double value, int decimals) {
    long long scale = 1;
    for (int i = 0; i < decimals; ++i) scale *= 10;
    long long fixed = std::llround(value * static_cast<double>(scale));
    unsigned long long magnitude = fixed < 0 ? 0ULL - static_cast<unsigned long long>(fixed) : fixed;
    std::string out = (fixed < 0 ? "-" : "") + std::to_string(magnitude / scale);
    std::string fraction;
    if (decimals > 0) {
        fraction = std::to_string(magnitude % scale);
        fraction.insert(0, static_cast<std::size_t>(decimals) - fraction.size(), '0');
    }
    while (!fraction.empty() && fraction.back() == '0') fraction.pop_back();
    if (!fraction.empty()) out += "." + fraction;
    return out;
}

std::string to_utf8(std::u32string_view text) {
    std::string out;
    for (char32_t cp : text) {
        if (cp < 0x80) {
            out.push_back(static_cast<char>(cp));
        } else if (cp < 0x800) {
            out.push_back(static_cast<char>(0xC0 | cp >> 6));
            out.push_back(static_cast<char>(0x80 | (cp & 0x3F)));
        } else if (cp < 0x10000) {
            out.push_back(static_cast<char>(0xE0 | cp >> 12));
            out.push_back(static_cast<char>(0x80 | (cp >> 6 & 0x3F)));
            out.push_back(static_cast<char>(0x80 | (cp & 0x3F)));
        } else {
            out.push_back(static_cast<char>(0xF0 | cp >> 18));
            out.push_back(static_cast<char>(0x80 | (cp >> 12 & 0x3F)));
            out.push_back(static_cast<char>(0x80 | (cp >> 6 & 0x3F)));
            out.push_back(static_cast<char>(0x80 | (cp & 0x3F)));
        }
    }
    return out;
}

std::string to_printable_ascii(std::u32string_view text) {
    std::string out;
    for (char32_t cp : text) out.push_back(cp >= 0x20 && cp < 0x7F ? static_cast<char>(cp) : '?');
    return out;
}

double helvetica_width(char32_t c) {
    // Advance widths of Helvetica in WinAnsiEncoding (1/1000 em), codes 32..126,
    // from the font's AFM metrics.
    static constexpr std::array<std::uint16_t, 95> kWidths = {
        278,  278, 355, 556, 556, 889, 667, 191, 333, 333, 389, 584, 278, 333, 278, 278,  // space .. /
        556,  556, 556, 556, 556, 556, 556, 556, 556, 556, 278, 278, 584, 584, 584, 556,  // 0 .. ?
        1015, 667, 667, 722, 722, 667, 611, 778, 722, 278, 500, 667, 556, 833, 722, 778,  // @ .. O
        667,  778, 722, 667, 611, 722, 667, 944, 667, 667, 611, 278, 278, 278, 469, 556,  // P .. _
        333,  556, 556, 500, 556, 556, 278, 556, 556, 222, 222, 500, 222, 833, 556, 556,  // ` .. o
        556,  556, 333, 500, 278, 556, 500, 722, 500, 500, 500, 334, 260, 334, 584};      // p .. ~
    return c >= 32 && c < 127 ? kWidths[c - 32] / 1000.0 : 0.556;
}

CaptionBox vector_caption_box(const Style& style) {
    if (style.caption.empty()) return {};
    double em = 0;
    for (char32_t c : style.caption) em += helvetica_width(c);
    // One module tall type reads well at any module size; long captions shrink to fit.
    double usable = 0.9 * style.cols;
    double font_size = em > usable ? usable / em : 1.0;
    CaptionBox box;
    box.font_size = font_size;
    box.band = 2 * font_size;
    box.baseline = style.rows + 1.25 * font_size;
    box.width = em * font_size;
    box.left = (style.cols - box.width) / 2;
    return box;
}

}  // namespace render_detail

const char* to_string(ImageFormat format) {
    switch (format) {
        case ImageFormat::png: return "png";
        case ImageFormat::svg: return "svg";
        case ImageFormat::pdf: return "pdf";
    }
    return "?";
}

ImageFormat image_format_for_path(const std::string& path) {
    std::size_t slash = path.find_last_of("/\\");
    std::size_t dot = path.find_last_of('.');
    std::string ext;
    if (dot != std::string::npos && (slash == std::string::npos || dot > slash)) ext = path.substr(dot + 1);
    std::transform(ext.begin(), ext.end(), ext.begin(),
                   [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
    if (ext == "png") return ImageFormat::png;
    if (ext == "svg") return ImageFormat::svg;
    if (ext == "pdf") return ImageFormat::pdf;
    throw std::invalid_argument("cannot tell the image format of '" + path +
                                "': the file name must end in .png, .svg or .pdf");
}

std::string render_field(const Field& field, ImageFormat format, const RenderOptions& options) {
    render_detail::Style style = render_detail::make_style(field, options);
    switch (format) {
        case ImageFormat::png: return render_detail::render_png(field, style, options);
        case ImageFormat::svg: return render_detail::render_svg(field, style, options);
        case ImageFormat::pdf: return render_detail::render_pdf(field, style, options);
    }
    throw std::invalid_argument("unknown image format " + std::to_string(static_cast<int>(format)));
}

}  // namespace umf
