// The marker field model: an h x w array of modules with values 0..k-1.
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

namespace umf {

// How windows are compared. Binary fields compare module values; k-ary
// fields compare the signs of the differences across module edges, because
// absolute shades cannot be recovered under unknown lighting.
enum class WindowKey { modules, edges };

const char* to_string(WindowKey key);

// Limits that keep a field file from asking for absurd amounts of memory.
// A 4-orientable field cannot exceed a few hundred modules per side for any
// supported window and colour count, so 4096 is generous.
inline constexpr int kMaxFieldSide = 4096;
inline constexpr int kMinColors = 2;
inline constexpr int kMaxColors = 10;  // one decimal digit per module in the file
inline constexpr std::size_t kMaxScreenNameBytes = 255;  // a host name's limit

struct Field {
    std::string id;
    int width = 0;
    int height = 0;
    int window = 4;  // n: windows are n x n modules; 3 or 4
    int colors = 2;  // k
    WindowKey key = WindowKey::modules;
    std::vector<std::string> palette;  // "#rrggbb", one per colour
    std::vector<std::uint8_t> modules;  // row-major, height * width values
    // The screen this field was made for, as people name it (a screen's own
    // field); empty for a field any screen may show. Printed with the field.
    std::string screen;

    std::uint8_t at(int row, int col) const { return modules[static_cast<std::size_t>(row) * width + col]; }
    std::uint8_t& at(int row, int col) { return modules[static_cast<std::size_t>(row) * width + col]; }

    int window_rows() const { return height - window + 1; }
    int window_cols() const { return width - window + 1; }
    long window_count() const { return static_cast<long>(window_rows()) * window_cols(); }
};

// A field of the given shape with all modules 0 and the default palette.
Field make_field(int width, int height, int window, int colors, WindowKey key, std::string id = {});

// The key that suits a colour count: modules for binary, edges otherwise.
WindowKey default_key(int colors);

// True for "#rrggbb" (either case), the form palettes are written in.
bool is_hex_colour(const std::string& s);

// Evenly spaced greys from black to white.
std::vector<std::string> grey_palette(int colors);

// The usual id: "b4-64x36" for binary, "k3e3-64x36" for k-ary with edge key,
// followed by "-s<seed>" when a seed is given.
std::string default_field_id(int width, int height, int window, int colors, WindowKey key);

// Empty when the field's shape, values and palette are consistent; otherwise
// the first problem found, in words.
std::string describe_invalid(const Field& field);

// Upper bound on the number of windows of a 4-orientable field: eq. 8 of the
// method for module keys; for edge keys the number of distinct edge-sign
// patterns over four (see field.cpp).
double window_count_bound(int window, int colors, WindowKey key);

}  // namespace umf
