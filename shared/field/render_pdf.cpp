// PDF output: a hand-written PDF 1.4 file with one page, its content stream
// compressed with the PNG writer's zlib encoder.
#include <cstdio>
#include <map>

#include "shared/field/render_internal.hpp"
#include "shared/io/pdf_objects.hpp"

namespace umf::render_detail {

namespace {

std::string pdf_string(std::string_view ascii) {
    std::string out = "(";
    for (char c : ascii) {
        if (c == '(' || c == ')' || c == '\\') out.push_back('\\');
        out.push_back(c);
    }
    return out + ")";
}

std::string fill_colour(const Rgb& c) {
    return format_number(c[0] / 255.0) + " " + format_number(c[1] / 255.0) + " " + format_number(c[2] / 255.0) +
           " rg\n";
}

// Page content: rectangles in module units through a flipped matrix, so that
// they keep integer coordinates with row 0 at the top; the caption in plain
// page coordinates, since text under a flipped matrix would be upside down.
std::string page_content(const Field& field, const Style& style, const CaptionBox& caption, double unit,
                         double page_height) {
    std::string out = "q\n" + format_number(unit, 6) + " 0 0 " + format_number(-unit, 6) + " 0 " +
                      format_number(page_height, 6) + " cm\n";
    out += fill_colour(style.palette[style.light]);
    out += "0 0 " + std::to_string(style.cols) + " " + format_number(style.rows + caption.band, 6) + " re f\n";
    std::map<std::uint8_t, std::string> paths;
    for (const Run& run : horizontal_runs(field)) {
        if (run.value == style.light) continue;
        paths[run.value] += std::to_string(style.quiet + run.col) + " " + std::to_string(style.quiet + run.row) + " " +
                            std::to_string(run.length) + " 1 re\n";
    }
    for (const auto& [value, path] : paths) out += fill_colour(style.palette[value]) + path + "f\n";
    out += "Q\n";
    if (caption.font_size > 0) {
        out += fill_colour(style.palette[style.dark]);
        out += "BT\n/F1 " + format_number(caption.font_size * unit, 6) + " Tf\n" +
               format_number(caption.left * unit, 6) + " " + format_number(page_height - caption.baseline * unit, 6) +
               " Td\n" + pdf_string(to_printable_ascii(style.caption)) + " Tj\nET\n";
    }
    return out;
}

}  // namespace

std::string render_pdf(const Field& field, const Style& style, const RenderOptions& options) {
    CaptionBox caption = vector_caption_box(style);
    double unit = options.module_mm > 0 ? options.module_mm / 25.4 * 72 : module_units(options);  // points per module
    double page_width = style.cols * unit;
    double page_height = (style.rows + caption.band) * unit;
    std::string content = zlib_compress(page_content(field, style, caption, unit, page_height));

    std::vector<std::string> objects = {
        "<< /Type /Catalog /Pages 2 0 R >>",
        "<< /Type /Pages /Kids [3 0 R] /Count 1 >>",
        "<< /Type /Page /Parent 2 0 R /MediaBox [0 0 " + format_number(page_width) + " " + format_number(page_height) +
            "] /Resources << /Font << /F1 5 0 R >> >> /Contents 4 0 R >>",
        "<< /Length " + std::to_string(content.size()) + " /Filter /FlateDecode >>\nstream\n" + content + "\nendstream",
        "<< /Type /Font /Subtype /Type1 /BaseFont /Helvetica /Encoding /WinAnsiEncoding >>",
        "<< /Title " + pdf_string(to_printable_ascii(decode_text(field.id))) + " /Producer (umf) >>",
    };

    return io::pdf_from_objects(objects, 6);
}

}  // namespace umf::render_detail
