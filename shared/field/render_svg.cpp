// SVG output: the viewBox is in module units, so every rectangle has integer
// coordinates and the physical size lives only in the width/height attributes.
#include <map>

#include "shared/field/render_internal.hpp"

namespace umf::render_detail {

namespace {

std::string xml_escape(std::string_view text) {
    std::string out;
    for (char c : text) {
        switch (c) {
            case '&': out += "&amp;"; break;
            case '<': out += "&lt;"; break;
            case '>': out += "&gt;"; break;
            case '"': out += "&quot;"; break;
            default: out.push_back(c);
        }
    }
    return out;
}

}  // namespace

std::string render_svg(const Field& field, const Style& style, const RenderOptions& options) {
    CaptionBox caption = vector_caption_box(style);
    double height = style.rows + caption.band;
    bool physical = options.module_mm > 0;
    double unit = physical ? options.module_mm : module_units(options);
    std::string suffix = physical ? "mm" : "";

    std::string svg = "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n";
    svg += "<svg xmlns=\"http://www.w3.org/2000/svg\" version=\"1.1\" width=\"" + format_number(style.cols * unit) +
           suffix + "\" height=\"" + format_number(height * unit) + suffix + "\" viewBox=\"0 0 " +
           std::to_string(style.cols) + " " + format_number(height, 6) + "\" shape-rendering=\"crispEdges\">\n";
    if (!field.id.empty()) svg += "<title>" + xml_escape(to_utf8(decode_text(field.id))) + "</title>\n";
    // The background doubles as quiet zone, caption band and every module of
    // the lightest colour, which are therefore not drawn again.
    svg += "<rect x=\"0\" y=\"0\" width=\"" + std::to_string(style.cols) + "\" height=\"" + format_number(height, 6) +
           "\" fill=\"" + hex_colour(style.palette[style.light]) + "\"/>\n";

    std::map<std::uint8_t, std::string> rects_by_value;
    for (const Run& run : horizontal_runs(field)) {
        if (run.value == style.light) continue;
        rects_by_value[run.value] += "<rect x=\"" + std::to_string(style.quiet + run.col) + "\" y=\"" +
                                     std::to_string(style.quiet + run.row) + "\" width=\"" +
                                     std::to_string(run.length) + "\" height=\"1\"/>\n";
    }
    for (const auto& [value, rects] : rects_by_value)
        svg += "<g fill=\"" + hex_colour(style.palette[value]) + "\">\n" + rects + "</g>\n";

    if (caption.font_size > 0) {
        svg += "<text x=\"" + format_number(style.cols / 2.0) + "\" y=\"" + format_number(caption.baseline, 6) +
               "\" xml:space=\"preserve\" font-family=\"Helvetica, Arial, sans-serif\" font-size=\"" +
               format_number(caption.font_size, 6) + "\" text-anchor=\"middle\" fill=\"" +
               hex_colour(style.palette[style.dark]) + "\">" + xml_escape(to_utf8(style.caption)) + "</text>\n";
    }
    svg += "</svg>\n";
    return svg;
}

}  // namespace umf::render_detail
