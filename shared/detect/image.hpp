// Image views the detector reads: it never owns or copies the caller's
// pixels, except to turn colour into one grey channel.
#pragma once

#include <cstddef>
#include <cstdint>
#include <limits>
#include <string>
#include <vector>

namespace umf {

struct GreyView {
    const std::uint8_t* data = nullptr;
    int width = 0;
    int height = 0;
    std::ptrdiff_t stride = 0;  // bytes from one row to the next; may exceed width

    std::uint8_t at(int x, int y) const { return data[y * stride + x]; }
    const std::uint8_t* row(int y) const { return data + y * stride; }
};

// Limits on what the detector accepts: 16384 pixels a side is beyond any camera.
inline constexpr int kMaxImageSideForDetection = 16384;

// Empty when the view can be read; otherwise what is wrong with it.
std::string describe_invalid(const GreyView& image);

// Reads one byte of every 64 bytes of the image, row after row. A camera
// frame written by the device, or one of many held in memory, is not in the
// processor's cache; a tracked frame's reads land all over it (module edges
// along every grid line, every module's centre), each one a wait on memory.
// In order, the processor fetches the rows ahead of the reads at the
// memory's full speed. On a frame already in cache it costs a few
// microseconds at 640 x 480.
void bring_into_cache(const GreyView& image);

enum class PixelOrder { rgb, bgr, rgba, bgra };

struct ColourView {
    const std::uint8_t* data = nullptr;
    int width = 0;
    int height = 0;
    std::ptrdiff_t stride = 0;
    PixelOrder order = PixelOrder::rgba;
};

// Empty when the colour view can be read; otherwise what is wrong with it.
std::string describe_invalid(const ColourView& image);

// The Sobel gradient at an interior pixel (1 <= x < width - 1, likewise y),
// pointing from dark to bright.
inline void sobel(const GreyView& im, int x, int y, float& gx, float& gy) {
    const std::uint8_t* a = im.row(y - 1) + x;
    const std::uint8_t* b = im.row(y) + x;
    const std::uint8_t* c = im.row(y + 1) + x;
    gx = static_cast<float>((a[1] + 2 * b[1] + c[1]) - (a[-1] + 2 * b[-1] + c[-1]));
    gy = static_cast<float>((c[-1] + 2 * c[0] + c[1]) - (a[-1] + 2 * a[0] + a[1]));
}

// The image at (x, y), pixel centres at +0.5, interpolated between the four
// nearest pixels; NaN where they are not all inside the image.
inline double bilinear(const GreyView& im, double x, double y) {
    x -= 0.5;
    y -= 0.5;
    // Inside, truncation is the floor (and no far-off point overflows an int).
    if (!(x >= 0 && y >= 0 && x < im.width - 1 && y < im.height - 1)) return std::numeric_limits<double>::quiet_NaN();
    const int x0 = static_cast<int>(x), y0 = static_cast<int>(y);
    const double fx = x - x0, fy = y - y0;
    const std::uint8_t* r0 = im.row(y0) + x0;
    const std::uint8_t* r1 = im.row(y0 + 1) + x0;
    return (r0[0] * (1 - fx) + r0[1] * fx) * (1 - fy) + (r1[0] * (1 - fx) + r1[1] * fx) * fy;
}

// The image at half its width and height, each pixel the mean of a 2 x 2
// block, into `out` (reused between frames); a view of it. A point (x, y)
// of `image` is (x / 2, y / 2) in it. An odd last row or column is dropped.
GreyView half_size(const GreyView& image, std::vector<std::uint8_t>& out);

// The image at twice its width and height, interpolated with a cubic (Keys,
// a = -0.75) through the pixel centres, into `out`; a view of it. A point
// (x, y) of `image` is (2x, 2y) in it.
GreyView double_size(const GreyView& image, std::vector<std::uint8_t>& out);

// The image through a binomial filter (1 8 28 56 70 56 28 8 1) / 256 along
// rows and columns, a Gaussian of sigma sqrt(2), into `out` (reused between
// frames); a view of it at the same size. A hatch of 2-3 px keeps under
// 1 % of its swing, one of 5 px a fifth; an edge keeps its whole step,
// spread over some 5 px.
GreyView smoothed(const GreyView& image, std::vector<std::uint8_t>& out);

// Luma (BT.601 weights in integers) of a colour image into `out`, reused
// between frames; returns a view of it. Throws std::invalid_argument for a
// view describe_invalid rejects.
GreyView to_luma(const ColourView& image, std::vector<std::uint8_t>& out);

}  // namespace umf
