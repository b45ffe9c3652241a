// overlay::mix_field, the provider's mixing, against the camera simulator's
// reference (tests/sim/field_mix.hpp): the same bytes, in every byte order.
#include "shared/overlay/field_mix.hpp"

#include <gtest/gtest.h>

#include <opencv2/core.hpp>
#include <opencv2/imgproc.hpp>

#include <cmath>
#include <random>
#include <string>

#include "shared/field/field_io.hpp"
#include "tests/sim/field_mix.hpp"
#include "tests/support/shipped_field.hpp"

namespace {

using namespace umf;
using umf::test::shipped_field;

cv::Mat random_image(cv::Size size, int type, unsigned seed) {
    cv::Mat m(size, type);
    cv::RNG rng(seed);
    rng.fill(m, cv::RNG::UNIFORM, 0, 256);
    return m;
}

overlay::PixelBuffer buffer_of(cv::Mat& m, bool bgr) {
    return {m.data, m.cols, m.rows, static_cast<std::ptrdiff_t>(m.step), m.channels(), bgr};
}

TEST(FieldMix, MatchesTheSimulatorByteForByte) {
    for (const char* name : {"b4-64x36.json", "k3e4-64x36.json"}) {
        const Field field = shipped_field(name);
        const cv::Mat screen = random_image({701, 419}, CV_8UC3, 7);
        // Fractional origin and module size, the field reaching past the right and bottom edges.
        const overlay::FieldPlacement placement{13.37, -21.71, 11.23};
        const sim::FieldPlacement reference_placement{{placement.origin_x, placement.origin_y}, placement.module_px};
        for (double opacity : {0.3, 0.5, 0.0625, 1.0}) {
            const cv::Mat expected = sim::mix_field(screen, field, reference_placement, opacity);

            cv::Mat bgr = screen.clone();
            overlay::mix_field(buffer_of(bgr, true), field, placement, opacity);
            EXPECT_EQ(cv::norm(bgr, expected, cv::NORM_INF), 0) << name << " opacity " << opacity;

            // RGB byte order: the same pixels with red and blue swapped.
            cv::Mat rgb;
            cv::cvtColor(screen, rgb, cv::COLOR_BGR2RGB);
            overlay::mix_field(buffer_of(rgb, false), field, placement, opacity);
            cv::Mat back;
            cv::cvtColor(rgb, back, cv::COLOR_RGB2BGR);
            EXPECT_EQ(cv::norm(back, expected, cv::NORM_INF), 0) << name << " opacity " << opacity;

            // Four channels, in a buffer with padding after each row: colour
            // as above, the fourth byte untouched.
            cv::Mat wide = random_image({701 * 4 + 12, 419}, CV_8UC1, 3);
            cv::Mat bgra = wide(cv::Rect(0, 0, 701 * 4, 419)).reshape(4);
            const cv::Mat alpha_before = [&] {
                cv::Mat a;
                cv::extractChannel(bgra, a, 3);
                return a;
            }();
            cv::Mat colour_only;
            cv::cvtColor(screen, colour_only, cv::COLOR_BGR2BGRA);
            cv::insertChannel(alpha_before, colour_only, 3);
            colour_only.copyTo(bgra);
            overlay::mix_field(buffer_of(bgra, true), field, placement, opacity);
            cv::Mat alpha_after, colour_after;
            cv::extractChannel(bgra, alpha_after, 3);
            cv::cvtColor(bgra, colour_after, cv::COLOR_BGRA2BGR);
            EXPECT_EQ(cv::norm(alpha_after, alpha_before, cv::NORM_INF), 0);
            EXPECT_EQ(cv::norm(colour_after, expected, cv::NORM_INF), 0) << name << " opacity " << opacity;
        }
    }
}

TEST(FieldMix, OpacityZeroLeavesTheImageAsItWas) {
    const Field field = shipped_field("b4-64x36.json");
    const cv::Mat screen = random_image({640, 360}, CV_8UC3, 11);
    cv::Mat mixed = screen.clone();
    overlay::mix_field(buffer_of(mixed, true), field, {0.5, 0.25, 10.0}, 0.0);
    EXPECT_EQ(cv::norm(mixed, screen, cv::NORM_INF), 0);
}

TEST(FieldMix, UsesThePaletteGiven) {
    const Field field = shipped_field("b4-64x36.json");
    cv::Mat mixed(360, 640, CV_8UC3, cv::Scalar(0, 0, 0));
    const overlay::FieldPlacement placement{0, 0, 10};
    // At opacity 1 every pixel is its module's colour: red for 0, blue for 1 (BGR order in the Mat).
    overlay::mix_field(buffer_of(mixed, true), field, placement, 1.0, {"#ff0000", "#0000FF"});
    for (int i = 0; i < field.height; ++i)
        for (int j = 0; j < field.width; ++j) {
            const cv::Vec3b px = mixed.at<cv::Vec3b>(i * 10 + 5, j * 10 + 5);
            const cv::Vec3b want = field.at(i, j) == 0 ? cv::Vec3b(0, 0, 255) : cv::Vec3b(255, 0, 0);
            ASSERT_EQ(px, want) << "module " << i << "," << j;
        }
}

TEST(FieldMix, RefusesWhatCannotBeMixed) {
    const Field field = shipped_field("k3e4-64x36.json");
    cv::Mat m(100, 100, CV_8UC3, cv::Scalar::all(0));
    const overlay::FieldPlacement placement{0, 0, 10};
    EXPECT_THROW(overlay::mix_field(buffer_of(m, true), field, placement, 1.5), std::invalid_argument);
    EXPECT_THROW(overlay::mix_field(buffer_of(m, true), field, placement, std::nan("")), std::invalid_argument);
    EXPECT_THROW(overlay::mix_field(buffer_of(m, true), field, {0, 0, 0}, 0.5), std::invalid_argument);
    EXPECT_THROW(overlay::mix_field(buffer_of(m, true), field, placement, 0.5, {"#000000", "#ffffff"}),
                 std::invalid_argument);  // three colours needed
    EXPECT_THROW(overlay::mix_field(buffer_of(m, true), field, placement, 0.5, {"#000000", "#ffffff", "red"}),
                 std::invalid_argument);
    overlay::PixelBuffer bad = buffer_of(m, true);
    bad.stride_bytes = 10;
    EXPECT_THROW(overlay::mix_field(bad, field, placement, 0.5), std::invalid_argument);
    bad = buffer_of(m, true);
    bad.channels = 2;
    EXPECT_THROW(overlay::mix_field(bad, field, placement, 0.5), std::invalid_argument);
    // A placement far off the screen changes nothing and does not overflow.
    const cv::Mat before = m.clone();
    overlay::mix_field(buffer_of(m, true), field, {1e300, -1e300, 1e-3}, 1.0);
    EXPECT_EQ(cv::norm(m, before, cv::NORM_INF), 0);
}

}  // namespace
