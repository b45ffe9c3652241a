#include "shared/overlay/background_blur.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <vector>

namespace umf::overlay {

namespace {

// Three box passes: the result is within a few per cent of a Gaussian (a
// piecewise quadratic), which a fourth pass would not visibly improve, and
// each pass costs the same whatever its width.
constexpr int kPasses = 3;

// Beyond this nothing of the content's detail is left anyway, and it keeps
// the running sums (255 * width) exact in int and in float.
constexpr double kMaxSigmaPx = 4096.0;

// Radii of the passes whose variances add up to sigma^2: the odd widths on
// either side of the ideal one, as many of the smaller as brings the sum
// closest (Wells 1986; Kovesi, "Fast almost-Gaussian filtering", 2010). A
// single width would miss small sigmas by up to a whole pixel of width.
std::array<int, kPasses> pass_radii(double sigma) {
    const double variance = sigma * sigma;
    const double ideal = std::sqrt(12.0 * variance / kPasses + 1.0);
    int lower = static_cast<int>(std::floor(ideal));
    if (lower % 2 == 0) --lower;
    const double n = kPasses;
    const double smaller = (12.0 * variance - n * lower * lower - 4.0 * n * lower - 3.0 * n) / (-4.0 * lower - 4.0);
    const int m = std::clamp(static_cast<int>(std::lround(smaller)), 0, kPasses);
    std::array<int, kPasses> radii{};
    for (int i = 0; i < kPasses; ++i) radii[i] = (i < m ? lower : lower + 2) / 2;
    return radii;
}

// Where position i (-r - 1 <= i <= n + r) of a line of n reads from: the
// line mirrored about its ends (..., 1, 0 | 0, 1, ... n - 1 | n - 1, ...),
// as often as a radius wider than the line needs. Mirroring keeps each pass
// a symmetric matrix, so the image's mean is kept exactly (up to rounding);
// repeating the end pixel instead would weight it r + 1 times and shift the
// mean of text near the box's border by a level or two. Either way nothing
// outside the box is read.
std::vector<int> mirrored(int n, int r) {
    std::vector<int> at(static_cast<std::size_t>(n) + 2 * static_cast<std::size_t>(r) + 2);
    const long period = 2L * n;
    for (std::size_t k = 0; k < at.size(); ++k) {
        long m = (static_cast<long>(k) - r - 1) % period;
        if (m < 0) m += period;
        at[k] = static_cast<int>(m < n ? m : period - 1 - m);
    }
    return at;
}

// The mean of `in` over x - r .. x + r (mirrored at the ends), three
// interleaved channels, rounded to nearest: the widths are odd, so no sum is
// ever half way and the rounding adds no bias to the image's mean.
void box_row(const std::uint8_t* in, std::uint8_t* out, int n, int r, const std::vector<int>& index) {
    const float scale = 1.0f / static_cast<float>(2 * r + 1);
    // index[x + r + 1] is where position x reads from.
    const int* at = index.data() + r + 1;
    int s0 = 0, s1 = 0, s2 = 0;
    for (int i = -r; i <= r; ++i) {
        const std::uint8_t* p = in + 3 * at[i];
        s0 += p[0], s1 += p[1], s2 += p[2];
    }
    for (int x = 0; x < n; ++x) {
        out[3 * x] = static_cast<std::uint8_t>(static_cast<float>(s0) * scale + 0.5f);
        out[3 * x + 1] = static_cast<std::uint8_t>(static_cast<float>(s1) * scale + 0.5f);
        out[3 * x + 2] = static_cast<std::uint8_t>(static_cast<float>(s2) * scale + 0.5f);
        const std::uint8_t* add = in + 3 * at[x + r + 1];
        const std::uint8_t* sub = in + 3 * at[x - r];
        s0 += add[0] - sub[0];
        s1 += add[1] - sub[1];
        s2 += add[2] - sub[2];
    }
}

// The same down the columns of `rows` rows of `row_len` bytes. A running sum
// per byte of the row, advanced a whole row at a time, reads memory in order
// and vectorises, where walking each column would miss the cache on every
// pixel.
void box_columns(const std::uint8_t* in, std::uint8_t* out, int rows, std::size_t row_len, int r,
                 std::vector<int>& sums) {
    const float scale = 1.0f / static_cast<float>(2 * r + 1);
    const std::vector<int> index = mirrored(rows, r);
    const int* at = index.data() + r + 1;
    const auto row = [&](int y) { return in + static_cast<std::size_t>(at[y]) * row_len; };
    sums.assign(row_len, 0);
    for (int i = -r; i <= r; ++i) {
        const std::uint8_t* p = row(i);
        for (std::size_t j = 0; j < row_len; ++j) sums[j] += p[j];
    }
    for (int y = 0; y < rows; ++y) {
        std::uint8_t* o = out + static_cast<std::size_t>(y) * row_len;
        for (std::size_t j = 0; j < row_len; ++j)
            o[j] = static_cast<std::uint8_t>(static_cast<float>(sums[j]) * scale + 0.5f);
        const std::uint8_t* add = row(y + r + 1);
        const std::uint8_t* sub = row(y - r);
        for (std::size_t j = 0; j < row_len; ++j) sums[j] += add[j] - sub[j];
    }
}

bool buffer_is_sound(const PixelBuffer& image) {
    if (image.channels != 3 && image.channels != 4) return false;
    if (image.width < 0 || image.height < 0) return false;
    if (image.width == 0 || image.height == 0) return true;
    return image.data && image.stride_bytes >= static_cast<std::ptrdiff_t>(image.width) * image.channels;
}

// First pixel whose centre has field coordinate >= 0 and one past the last
// whose centre is below `modules`, clipped to [0, pixels]: field_mix's rule,
// so the blur ends exactly where the field does.
std::pair<int, int> covered(double origin, double module_px, int modules, int pixels) {
    const auto clip = [pixels](double v) { return static_cast<int>(std::clamp(v, 0.0, static_cast<double>(pixels))); };
    return {clip(std::ceil(origin - 0.5)), clip(std::ceil(origin + module_px * modules - 0.5))};
}

}  // namespace

PixelBox field_pixels(const FieldPlacement& placement, int field_width, int field_height, int image_width,
                      int image_height) {
    if (field_width <= 0 || field_height <= 0 || image_width <= 0 || image_height <= 0) return {};
    if (!(placement.module_px > 0) || !std::isfinite(placement.module_px) || !std::isfinite(placement.origin_x) ||
        !std::isfinite(placement.origin_y))
        return {};
    const auto [x0, x1] = covered(placement.origin_x, placement.module_px, field_width, image_width);
    const auto [y0, y1] = covered(placement.origin_y, placement.module_px, field_height, image_height);
    return {x0, y0, x1, y1};
}

double blur_sigma_px(double strength, double module_px) {
    // Half a module at full strength: a Gaussian of that sigma keeps
    // exp(-2 pi^2 sigma^2 / period^2) of a pattern's contrast, under 1 % of
    // anything repeating within a module (letters, strokes, thin borders,
    // the detail that makes edgels at the field's own scale), about 30 % at
    // two modules and most of what is larger (windows, pictures), so the
    // screen stays recognisable. Linear in strength so the slider's middle
    // is a middle.
    if (!(strength > 0) || !(module_px > 0) || !std::isfinite(module_px)) return 0.0;
    return std::min(kMaxSigmaPx, std::min(strength, 1.0) * module_px / 2.0);
}

bool blur_background(const PixelBuffer& image, PixelBox box, double strength, double module_px) {
    if (!buffer_is_sound(image) || !(module_px > 0) || !std::isfinite(module_px)) return false;
    box.x0 = std::max(box.x0, 0);
    box.y0 = std::max(box.y0, 0);
    box.x1 = std::min(box.x1, image.width);
    box.y1 = std::min(box.y1, image.height);
    const double sigma = blur_sigma_px(strength, module_px);
    if (box.empty() || sigma <= 0.0) return true;
    const auto radii = pass_radii(sigma);
    if (std::all_of(radii.begin(), radii.end(), [](int r) { return r == 0; })) return true;

    const int w = box.x1 - box.x0;
    const int h = box.y1 - box.y0;
    const std::size_t row_len = static_cast<std::size_t>(w) * 3;
    const auto pixel = [&](int x, int y) {
        return image.data + static_cast<std::ptrdiff_t>(y) * image.stride_bytes +
               static_cast<std::ptrdiff_t>(x) * image.channels;
    };
    // The box's colour bytes, packed: the passes need not care about alpha
    // or strides.
    std::vector<std::uint8_t> a(row_len * static_cast<std::size_t>(h));
    std::vector<std::uint8_t> b(a.size());
    std::vector<std::uint8_t> t0(row_len), t1(row_len);
    std::array<std::vector<int>, kPasses> across;
    for (int i = 0; i < kPasses; ++i) across[i] = mirrored(w, radii[i]);
    for (int y = 0; y < h; ++y) {
        const std::uint8_t* src = pixel(box.x0, box.y0 + y);
        for (int x = 0; x < w; ++x, src += image.channels) std::copy(src, src + 3, &t0[3 * static_cast<std::size_t>(x)]);
        box_row(t0.data(), t1.data(), w, radii[0], across[0]);
        box_row(t1.data(), t0.data(), w, radii[1], across[1]);
        box_row(t0.data(), &a[static_cast<std::size_t>(y) * row_len], w, radii[2], across[2]);
    }
    std::vector<int> sums;
    box_columns(a.data(), b.data(), h, row_len, radii[0], sums);
    box_columns(b.data(), a.data(), h, row_len, radii[1], sums);
    box_columns(a.data(), b.data(), h, row_len, radii[2], sums);
    for (int y = 0; y < h; ++y) {
        const std::uint8_t* src = &b[static_cast<std::size_t>(y) * row_len];
        std::uint8_t* dst = pixel(box.x0, box.y0 + y);
        for (int x = 0; x < w; ++x, src += 3, dst += image.channels) std::copy(src, src + 3, dst);
    }
    return true;
}

bool blur_under_field(const PixelBuffer& image, int field_width, int field_height, const FieldPlacement& placement,
                      double strength) {
    if (!buffer_is_sound(image)) return false;
    const PixelBox box = field_pixels(placement, field_width, field_height, image.width, image.height);
    return blur_background(image, box, strength, placement.module_px);
}

}  // namespace umf::overlay
