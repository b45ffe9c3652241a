#include "shared/overlay/field_mix.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace umf::overlay {

namespace {

int hex_digit(char c) {
    if (c >= '0' && c <= '9') return c - '0';
    if (c >= 'a' && c <= 'f') return c - 'a' + 10;
    if (c >= 'A' && c <= 'F') return c - 'A' + 10;
    return -1;
}

std::array<std::uint8_t, 3> parse_colour(const std::string& hex) {
    if (!is_hex_colour(hex)) throw std::invalid_argument("palette entry \"" + hex + "\" is not #rrggbb");
    std::array<std::uint8_t, 3> rgb{};
    for (int c = 0; c < 3; ++c)
        rgb[c] = static_cast<std::uint8_t>(hex_digit(hex[1 + 2 * c]) * 16 + hex_digit(hex[2 + 2 * c]));
    return rgb;
}

// First pixel index whose centre has field coordinate >= 0, and one past the
// last whose centre is below `modules`, clipped to [0, pixels]. Clamped in
// double first so that a placement far off the screen cannot overflow int.
std::pair<int, int> covered_pixels(double origin, double module_px, int modules, int pixels) {
    const auto clip = [pixels](double v) { return static_cast<int>(std::clamp(v, 0.0, static_cast<double>(pixels))); };
    return {clip(std::ceil(origin - 0.5)), clip(std::ceil(origin + module_px * modules - 0.5))};
}

void check_buffer(const PixelBuffer& image) {
    if (image.channels != 3 && image.channels != 4)
        throw std::invalid_argument("mix_field: an image must have 3 or 4 channels, not " +
                                    std::to_string(image.channels));
    if (image.width < 0 || image.height < 0)
        throw std::invalid_argument("mix_field: image size " + std::to_string(image.width) + " x " +
                                    std::to_string(image.height) + " is negative");
    if (image.width == 0 || image.height == 0) return;
    if (!image.data) throw std::invalid_argument("mix_field: the image has no pixels");
    if (image.stride_bytes < static_cast<std::ptrdiff_t>(image.width) * image.channels)
        throw std::invalid_argument("mix_field: stride " + std::to_string(image.stride_bytes) +
                                    " bytes is below the row's " + std::to_string(image.width * image.channels));
}

}  // namespace

std::vector<std::array<std::uint8_t, 3>> field_colours_rgb(const Field& field, const std::vector<std::string>& palette) {
    const std::vector<std::string> own = field.palette.empty() ? grey_palette(field.colors) : field.palette;
    const std::vector<std::string>& hex = palette.empty() ? own : palette;
    if (hex.size() < static_cast<std::size_t>(field.colors))
        throw std::invalid_argument("palette has " + std::to_string(hex.size()) + " colours, field " + field.id +
                                    " needs " + std::to_string(field.colors));
    std::vector<std::array<std::uint8_t, 3>> out;
    for (const auto& c : hex) out.push_back(parse_colour(c));
    return out;
}

void mix_field(const PixelBuffer& image, const Field& field, const FieldPlacement& placement, double opacity,
               const std::vector<std::string>& palette) {
    check_buffer(image);
    if (!(placement.module_px > 0) || !std::isfinite(placement.module_px) || !std::isfinite(placement.origin_x) ||
        !std::isfinite(placement.origin_y))
        throw std::invalid_argument("mix_field: the placement needs a finite origin and a positive module size");
    if (!(opacity >= 0.0 && opacity <= 1.0))
        throw std::invalid_argument("mix_field: opacity must be 0..1, not " + std::to_string(opacity));
    if (field.width <= 0 || field.height <= 0 ||
        field.modules.size() != static_cast<std::size_t>(field.width) * static_cast<std::size_t>(field.height))
        throw std::invalid_argument("mix_field: field " + field.id + " has no modules or the wrong number of them");
    const auto colours = field_colours_rgb(field, palette);
    for (std::uint8_t m : field.modules)
        if (m >= colours.size())
            throw std::invalid_argument("mix_field: field " + field.id + " has a module value outside its palette");
    if (opacity == 0.0 || image.width == 0 || image.height == 0) return;

    // The blend of every content byte with every colour channel, computed by
    // the reference's formula and rounding (OpenCV's saturate_cast rounds
    // half to even, as lrint does), once instead of per pixel.
    std::vector<std::array<std::array<std::uint8_t, 256>, 3>> blend(colours.size());
    for (std::size_t k = 0; k < colours.size(); ++k)
        for (int c = 0; c < 3; ++c)
            for (int content = 0; content < 256; ++content) {
                const double mixed = (1 - opacity) * content + opacity * colours[k][c];
                blend[k][c][content] = static_cast<std::uint8_t>(std::clamp(std::lrint(mixed), 0L, 255L));
            }

    const auto [x0, x1] = covered_pixels(placement.origin_x, placement.module_px, field.width, image.width);
    const auto [y0, y1] = covered_pixels(placement.origin_y, placement.module_px, field.height, image.height);
    std::vector<int> column(static_cast<std::size_t>(std::max(0, x1 - x0)));
    for (int x = x0; x < x1; ++x) {
        double u = 0, v = 0;
        screen_to_field(placement, x + 0.5, 0.0, u, v);
        column[x - x0] = std::clamp(static_cast<int>(std::floor(u)), 0, field.width - 1);
    }
    // Byte offsets of red, green and blue within a pixel.
    const int red = image.bgr ? 2 : 0;
    const int blue = image.bgr ? 0 : 2;
    for (int y = y0; y < y1; ++y) {
        double u = 0, v = 0;
        screen_to_field(placement, 0.0, y + 0.5, u, v);
        const int row = std::clamp(static_cast<int>(std::floor(v)), 0, field.height - 1);
        std::uint8_t* px = image.data + y * image.stride_bytes + static_cast<std::ptrdiff_t>(x0) * image.channels;
        for (int x = x0; x < x1; ++x, px += image.channels) {
            const auto& table = blend[field.at(row, column[x - x0])];
            px[red] = table[0][px[red]];
            px[1] = table[1][px[1]];
            px[blue] = table[2][px[blue]];
        }
    }
}

}  // namespace umf::overlay
