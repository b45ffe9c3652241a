#include "shared/field/field.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>

namespace umf {

const char* to_string(WindowKey key) { return key == WindowKey::modules ? "modules" : "edges"; }

WindowKey default_key(int colors) { return colors <= 2 ? WindowKey::modules : WindowKey::edges; }

std::vector<std::string> grey_palette(int colors) {
    std::vector<std::string> out;
    for (int i = 0; i < colors; ++i) {
        int v = colors <= 1 ? 0 : static_cast<int>(std::lround(255.0 * i / (colors - 1)));
        char buf[8];
        std::snprintf(buf, sizeof buf, "#%02x%02x%02x", v, v, v);
        out.emplace_back(buf);
    }
    return out;
}

std::string default_field_id(int width, int height, int window, int colors, WindowKey key) {
    std::string prefix = colors == 2 && key == WindowKey::modules
                             ? "b" + std::to_string(window)
                             : "k" + std::to_string(colors) + (key == WindowKey::edges ? "e" : "m") +
                                   std::to_string(window);
    return prefix + "-" + std::to_string(width) + "x" + std::to_string(height);
}

Field make_field(int width, int height, int window, int colors, WindowKey key, std::string id) {
    Field f;
    f.width = width;
    f.height = height;
    f.window = window;
    f.colors = colors;
    f.key = key;
    f.id = id.empty() ? default_field_id(width, height, window, colors, key) : std::move(id);
    f.palette = grey_palette(colors);
    f.modules.assign(static_cast<std::size_t>(width) * height, 0);
    return f;
}

bool is_hex_colour(const std::string& s) {
    if (s.size() != 7 || s[0] != '#') return false;
    for (std::size_t i = 1; i < 7; ++i) {
        char c = s[i];
        bool hex = (c >= '0' && c <= '9') || (c >= 'a' && c <= 'f') || (c >= 'A' && c <= 'F');
        if (!hex) return false;
    }
    return true;
}

std::string describe_invalid(const Field& f) {
    if (f.window != 3 && f.window != 4) return "window must be 3 or 4, not " + std::to_string(f.window);
    if (f.colors < kMinColors || f.colors > kMaxColors)
        return "colors must be between " + std::to_string(kMinColors) + " and " + std::to_string(kMaxColors) +
               ", not " + std::to_string(f.colors);
    if (f.width < f.window || f.height < f.window)
        return "a " + std::to_string(f.width) + " x " + std::to_string(f.height) + " field has no " +
               std::to_string(f.window) + " x " + std::to_string(f.window) + " window";
    if (f.width > kMaxFieldSide || f.height > kMaxFieldSide)
        return "sides above " + std::to_string(kMaxFieldSide) + " modules are not supported (" +
               std::to_string(f.width) + " x " + std::to_string(f.height) + ")";
    if (f.modules.size() != static_cast<std::size_t>(f.width) * f.height)
        return "module count " + std::to_string(f.modules.size()) + " does not match " + std::to_string(f.width) +
               " x " + std::to_string(f.height);
    for (std::size_t i = 0; i < f.modules.size(); ++i)
        if (f.modules[i] >= f.colors)
            return "module at row " + std::to_string(i / f.width) + ", column " + std::to_string(i % f.width) +
                   " has value " + std::to_string(f.modules[i]) + ", outside 0.." + std::to_string(f.colors - 1);
    if (!f.palette.empty()) {
        if (static_cast<int>(f.palette.size()) != f.colors)
            return "palette has " + std::to_string(f.palette.size()) + " entries for " + std::to_string(f.colors) +
                   " colours";
        for (const auto& c : f.palette)
            if (!is_hex_colour(c)) return "palette entry '" + c + "' is not a #rrggbb colour";
    }
    return {};
}

double window_count_bound(int window, int colors, WindowKey key) {
    const int cells = window * window;
    if (key == WindowKey::modules) {
        // Patterns, less those equal to their own half-turn, in groups of four rotations.
        return (std::pow(colors, cells) - std::pow(colors, (cells + 1) / 2)) / 4.0;
    }
    // Edge signs come from module values, and adding a constant to every
    // module keeps the signs, so there are no more sign patterns than module
    // patterns whose smallest value is 0; nor more than 3^edges.
    const double signs = std::pow(3.0, 2 * window * (window - 1));
    const double shifted = std::pow(colors, cells) - std::pow(colors - 1, cells);
    return std::min(signs, shifted) / 4.0;
}

}  // namespace umf
