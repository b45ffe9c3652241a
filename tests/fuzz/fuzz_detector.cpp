// The detector (shared/detect/detector.hpp) on any image: whatever a camera
// or a hostile page hands it. The first bytes choose the image's size (up
// to 640 x 480, zero included), its row padding, the call (a search, a
// search around an aim, the video path's follow from a predicted place, a
// colour frame) and its aim and prediction; the rest are the pixels,
// repeated to fill the image, so a short input still makes a large frame
// and a periodic one (what the lattice search looks for).
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "shared/detect/detector.hpp"
#include "shared/field/field_io.hpp"

namespace {

constexpr int kMaxWidth = 640;
constexpr int kMaxHeight = 480;
constexpr std::size_t kHeaderBytes = 12;

const umf::Detector& detector() {
    static const umf::Detector d(umf::load_field(std::string(UMF_DATA_DIR) + "/fields/b4-64x36.json"));
    return d;
}

struct Header {
    const std::uint8_t* bytes;
    int u16(std::size_t at) const { return bytes[at] | bytes[at + 1] << 8; }
    double fraction(std::size_t at) const { return u16(at) / 65535.0; }
};

std::vector<std::uint8_t> pixels(const std::uint8_t* data, std::size_t size, std::size_t count) {
    std::vector<std::uint8_t> out(count, 0);
    if (size == 0) return out;
    for (std::size_t i = 0; i < count; ++i) out[i] = data[i % size];
    return out;
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    if (size < kHeaderBytes) return 0;
    const Header h{data};
    const int width = h.u16(0) % (kMaxWidth + 1);
    const int height = h.u16(2) % (kMaxHeight + 1);
    const int mode = data[4] & 3;
    const int padding = data[4] >> 5;  // 0..7 bytes beyond each row
    const Eigen::Vector2d aim(h.fraction(5) * width, h.fraction(7) * height);
    const std::uint8_t* rest = data + kHeaderBytes;
    const std::size_t rest_size = size - kHeaderBytes;

    if (mode == 3) {
        const std::ptrdiff_t stride = 4 * static_cast<std::ptrdiff_t>(width) + padding;
        const auto image = pixels(rest, rest_size, static_cast<std::size_t>(stride) * height);
        const auto order = static_cast<umf::PixelOrder>(data[9] & 3);
        const std::ptrdiff_t colour_stride = (order == umf::PixelOrder::rgb || order == umf::PixelOrder::bgr)
                                                 ? 3 * static_cast<std::ptrdiff_t>(width) + padding
                                                 : stride;
        (void)detector().detect(umf::ColourView{image.data(), width, height, colour_stride, order});
        return 0;
    }
    const std::ptrdiff_t stride = width + padding;
    const auto image = pixels(rest, rest_size, static_cast<std::size_t>(stride) * height);
    const umf::GreyView view{image.data(), width, height, stride};
    if (mode == 0) {
        (void)detector().detect(view);
    } else if (mode == 1) {
        (void)detector().detect(view, aim);
    } else {
        // A prediction as the tracker makes one: image to field, a turn, a
        // scale of 1/40 to 1/2 module a pixel and an offset within the field.
        const double turn = data[9] / 256.0 * 2.0 * M_PI;
        const double scale = 0.025 + data[10] / 255.0 * 0.475;
        const double offset = data[11] / 255.0 * 36.0;
        Eigen::Matrix3d predicted;
        predicted << scale * std::cos(turn), -scale * std::sin(turn), offset,
                     scale * std::sin(turn), scale * std::cos(turn), offset,
                     0.0, 0.0, 1.0;
        (void)detector().follow(view, aim, predicted);
    }
    return 0;
}
