// overlay::blur_background, the blur under the field (a preset's `blur`):
// nothing at strength 0, a Gaussian of half a module at 1, only within its
// box, the image's mean kept, and no size too odd for it.
#include "shared/overlay/background_blur.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <iostream>
#include <random>
#include <string>
#include <vector>

#include "shared/field/field_io.hpp"
#include "shared/overlay/field_mix.hpp"

namespace {

using namespace umf;
using overlay::PixelBox;

struct Image {
    int width = 0, height = 0, channels = 3;
    std::vector<std::uint8_t> bytes;
    overlay::PixelBuffer buffer() {
        return {bytes.data(), width, height, static_cast<std::ptrdiff_t>(width) * channels, channels, false};
    }
    std::uint8_t& at(int x, int y, int c) {
        return bytes[(static_cast<std::size_t>(y) * width + x) * channels + c];
    }
};

Image random_image(int width, int height, int channels, unsigned seed) {
    Image img{width, height, channels, std::vector<std::uint8_t>(static_cast<std::size_t>(width) * height * channels)};
    std::mt19937 rng(seed);
    std::uniform_int_distribution<int> byte(0, 255);
    for (auto& b : img.bytes) b = static_cast<std::uint8_t>(byte(rng));
    return img;
}

double channel_mean(const Image& img, int c) {
    double sum = 0;
    for (std::size_t i = c; i < img.bytes.size(); i += img.channels) sum += img.bytes[i];
    return sum / (static_cast<double>(img.width) * img.height);
}

PixelBox whole(const Image& img) { return {0, 0, img.width, img.height}; }

TEST(BackgroundBlur, StrengthZeroChangesNoByte) {
    for (int channels : {3, 4}) {
        Image img = random_image(321, 123, channels, 1);
        const auto before = img.bytes;
        ASSERT_TRUE(overlay::blur_background(img.buffer(), whole(img), 0.0, 30.0));
        EXPECT_EQ(img.bytes, before);
        ASSERT_TRUE(overlay::blur_background(img.buffer(), whole(img), std::nan(""), 30.0));
        EXPECT_EQ(img.bytes, before);
        // Too little to make a 3-pixel box: still nothing.
        ASSERT_TRUE(overlay::blur_background(img.buffer(), whole(img), 0.01, 30.0));
        EXPECT_EQ(img.bytes, before);
    }
    EXPECT_EQ(overlay::blur_sigma_px(0.0, 30.0), 0.0);
    EXPECT_EQ(overlay::blur_sigma_px(1.0, 30.0), 15.0);
    EXPECT_EQ(overlay::blur_sigma_px(0.5, 40.0), 10.0);
    EXPECT_EQ(overlay::blur_sigma_px(7.0, 40.0), 20.0);  // clamped to 1
}

TEST(BackgroundBlur, AFlatImageStaysFlat) {
    for (int channels : {3, 4}) {
        Image img{200, 90, channels, {}};
        for (int i = 0; i < img.width * img.height; ++i)
            for (int c = 0; c < channels; ++c) img.bytes.push_back(static_cast<std::uint8_t>(c == 3 ? 255 : 37 + 80 * c));
        const auto before = img.bytes;
        ASSERT_TRUE(overlay::blur_background(img.buffer(), {10, 5, 190, 80}, 1.0, 30.0));
        EXPECT_EQ(img.bytes, before);
    }
}

// A Gaussian of sigma spreads a step from 10 % to 90 % over 2 * 1.2816 sigma.
TEST(BackgroundBlur, AStepSpreadsOverAGaussiansWidth) {
    for (double module_px : {12.0, 30.0, 60.0}) {
        Image img{800, 24, 3, std::vector<std::uint8_t>(800 * 24 * 3, 0)};
        for (int y = 0; y < img.height; ++y)
            for (int x = img.width / 2; x < img.width; ++x)
                for (int c = 0; c < 3; ++c) img.at(x, y, c) = 255;
        ASSERT_TRUE(overlay::blur_background(img.buffer(), whole(img), 1.0, module_px));
        const auto crossing = [&](double level) {
            for (int x = 0; x + 1 < img.width; ++x) {
                const double a = img.at(x, 12, 1), b = img.at(x + 1, 12, 1);
                if (a < level && b >= level) return x + (level - a) / (b - a);
            }
            return -1.0;
        };
        const double width = crossing(0.9 * 255) - crossing(0.1 * 255);
        const double expected = 2 * 1.2816 * overlay::blur_sigma_px(1.0, module_px);
        EXPECT_NEAR(width, expected, 0.1 * expected + 1.0) << "module " << module_px;
        // Symmetric about the step; the rows all alike (a vertical blur of
        // equal rows changes nothing).
        EXPECT_NEAR(crossing(0.5 * 255), img.width / 2.0, 1.0);
        for (int y = 0; y < img.height; ++y) EXPECT_EQ(img.at(img.width / 2, y, 0), img.at(img.width / 2, 0, 0));
        // Half strength, half the spread.
        Image half{800, 24, 3, std::vector<std::uint8_t>(800 * 24 * 3, 0)};
        for (int y = 0; y < half.height; ++y)
            for (int x = half.width / 2; x < half.width; ++x) half.at(x, y, 0) = 255;
        ASSERT_TRUE(overlay::blur_background(half.buffer(), whole(half), 0.5, module_px));
        int ramp = 0;
        for (int x = 0; x < half.width; ++x) ramp += half.at(x, 12, 0) > 25 && half.at(x, 12, 0) < 230;
        EXPECT_NEAR(ramp, expected / 2, 0.15 * expected / 2 + 1.5) << "module " << module_px;
    }
}

TEST(BackgroundBlur, OnlyTheBoxChangesAndAlphaNever) {
    for (int channels : {3, 4}) {
        Image img = random_image(300, 200, channels, 2);
        Image before = img;
        const PixelBox box{50, 40, 250, 140};
        ASSERT_TRUE(overlay::blur_background(img.buffer(), box, 1.0, 20.0));
        int changed = 0;
        for (int y = 0; y < img.height; ++y)
            for (int x = 0; x < img.width; ++x) {
                const bool inside = x >= box.x0 && x < box.x1 && y >= box.y0 && y < box.y1;
                for (int c = 0; c < channels; ++c) {
                    const bool same = img.at(x, y, c) == before.at(x, y, c);
                    if (!inside || c == 3) {
                        ASSERT_TRUE(same) << x << ", " << y << ", channel " << c;
                    } else {
                        changed += !same;
                    }
                }
            }
        // Noise blurred by sigma 10 is near its mean: almost every byte moves.
        EXPECT_GT(changed, (box.x1 - box.x0) * (box.y1 - box.y0) * 3 * 9 / 10);
        // Near the mean, in fact: a byte of noise varies by 74 levels, a
        // mean of about 25 x 25 of them by 3.
        double spread = 0;
        for (int y = box.y0 + 20; y < box.y1 - 20; ++y)
            for (int x = box.x0 + 20; x < box.x1 - 20; ++x) spread = std::max(spread, std::abs(img.at(x, y, 0) - 127.5));
        EXPECT_LT(spread, 20.0);
    }
}

TEST(BackgroundBlur, TheMeanIsKept) {
    for (int channels : {3, 4}) {
        Image img = random_image(641, 359, channels, 3);
        // Text-like: dark strokes on light, where an edge clamp would show most.
        for (int y = 0; y < img.height; ++y)
            for (int x = 0; x < img.width; ++x)
                if ((x / 3) % 4 == 0 || (y % 17) < 2)
                    for (int c = 0; c < 3; ++c) img.at(x, y, c) = static_cast<std::uint8_t>(img.at(x, y, c) / 8);
        double before[3];
        for (int c = 0; c < 3; ++c) before[c] = channel_mean(img, c);
        ASSERT_TRUE(overlay::blur_background(img.buffer(), whole(img), 1.0, 30.0));
        for (int c = 0; c < 3; ++c) EXPECT_NEAR(channel_mean(img, c), before[c], 1.0) << "channel " << c;
    }
}

TEST(BackgroundBlur, OddSizesAndClippedBoxesNeverFail) {
    for (auto [w, h] : {std::pair{1, 1}, {2, 1}, {1, 2}, {7, 3}, {3, 301}, {301, 3}, {17, 13}}) {
        for (double module_px : {1.0, 4.0, 30.0, 256.0, 1e12}) {
            Image img = random_image(w, h, 3, 4);
            const double mean = channel_mean(img, 0);
            ASSERT_TRUE(overlay::blur_background(img.buffer(), {-5, -5, w + 5, h + 5}, 1.0, module_px));
            ASSERT_TRUE(overlay::blur_background(img.buffer(), {w / 2, h / 2, w * 3, h * 3}, 1.0, module_px));
            ASSERT_TRUE(overlay::blur_background(img.buffer(), {w, h, w + 9, h + 9}, 1.0, module_px));
            ASSERT_TRUE(overlay::blur_background(img.buffer(), {3, 3, 2, 2}, 1.0, module_px));
            if (w * h == 1) {
                EXPECT_EQ(channel_mean(img, 0), mean);
            }
        }
    }
    // A 1-pixel image under a box reaching past it: its one pixel stays.
    Image one{1, 1, 4, {10, 20, 30, 40}};
    ASSERT_TRUE(overlay::blur_background(one.buffer(), {-100, -100, 100, 100}, 1.0, 30.0));
    EXPECT_EQ(one.bytes, (std::vector<std::uint8_t>{10, 20, 30, 40}));
    // What the buffer cannot be, or a module size that is none: false, nothing changed.
    Image img = random_image(20, 10, 3, 5);
    const auto before = img.bytes;
    auto bad = img.buffer();
    bad.channels = 2;
    EXPECT_FALSE(overlay::blur_background(bad, whole(img), 1.0, 30.0));
    bad = img.buffer();
    bad.stride_bytes = 59;
    EXPECT_FALSE(overlay::blur_background(bad, whole(img), 1.0, 30.0));
    bad = img.buffer();
    bad.data = nullptr;
    EXPECT_FALSE(overlay::blur_background(bad, whole(img), 1.0, 30.0));
    bad = img.buffer();
    bad.width = -1;
    EXPECT_FALSE(overlay::blur_background(bad, whole(img), 1.0, 30.0));
    for (double module_px : {0.0, -3.0, std::nan(""), HUGE_VAL})
        EXPECT_FALSE(overlay::blur_background(img.buffer(), whole(img), 1.0, module_px)) << module_px;
    EXPECT_EQ(img.bytes, before);
    bad = img.buffer();
    bad.data = nullptr;
    bad.width = 0;  // an empty image is sound, and has nothing to blur
    EXPECT_TRUE(overlay::blur_background(bad, {0, 0, 5, 5}, 1.0, 30.0));
}

// field_pixels is the rule mix_field paints by: the pixels it changes are
// exactly the box, for fractional origins and modules, clipped at any side.
TEST(BackgroundBlur, FieldPixelsAreThePixelsTheFieldCovers) {
    const Field field = load_field(std::string(UMF_DATA_DIR) + "/fields/b4-64x36.json");
    for (const overlay::FieldPlacement placement :
         {overlay::FieldPlacement{13.37, -21.71, 11.23}, overlay::FieldPlacement{-40.5, 7.5, 9.0},
          overlay::FieldPlacement{0.49, 0.5, 4.0}, overlay::FieldPlacement{2000, 10, 8.0}}) {
        Image img{701, 419, 3, std::vector<std::uint8_t>(701 * 419 * 3, 128)};
        overlay::mix_field(img.buffer(), field, placement, 1.0, {"#000000", "#ffffff"});
        PixelBox changed{img.width, img.height, 0, 0};
        for (int y = 0; y < img.height; ++y)
            for (int x = 0; x < img.width; ++x)
                if (img.at(x, y, 0) != 128)
                    changed = {std::min(changed.x0, x), std::min(changed.y0, y), std::max(changed.x1, x + 1),
                               std::max(changed.y1, y + 1)};
        const PixelBox box = overlay::field_pixels(placement, field.width, field.height, img.width, img.height);
        if (changed.empty()) {
            EXPECT_TRUE(box.empty()) << placement.origin_x;
        } else {
            EXPECT_EQ(box, changed) << placement.origin_x << ", " << placement.origin_y;
        }
    }
    EXPECT_TRUE(overlay::field_pixels({0, 0, std::nan("")}, 10, 10, 100, 100).empty());
    EXPECT_TRUE(overlay::field_pixels({0, 0, 5}, 0, 10, 100, 100).empty());
}

// The figures for docs/BENCHMARKS.md: a full-HD screen under a field at
// 30-px modules, full strength, RGB and RGB32, and RGB at other module sizes
// (the cost must not grow with the radius). The bound only catches a blur
// whose cost grew with its radius: that would be some 10 times these.
TEST(BackgroundBlur, FullHdAtFullStrengthTakesFewMilliseconds) {
    for (auto [channels, module_px] : {std::pair{3, 30.0}, {4, 30.0}, {3, 8.0}, {3, 120.0}}) {
        Image img = random_image(1920, 1080, channels, 6);
        double best_ms = 1e9;
        for (int run = 0; run < 5; ++run) {
            const auto start = std::chrono::steady_clock::now();
            ASSERT_TRUE(overlay::blur_background(img.buffer(), whole(img), 1.0, module_px));
            best_ms = std::min(best_ms,
                               std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count());
        }
        std::cout << "[ blur     ] 1920 x 1080, " << channels << " bytes a pixel, " << module_px
                  << "-px modules, strength 1: " << best_ms << " ms (best of 5)\n";
        RecordProperty("ms_" + std::to_string(channels) + "_" + std::to_string(static_cast<int>(module_px)),
                       std::to_string(best_ms));
#ifdef NDEBUG
        EXPECT_LT(best_ms, 400.0);
#endif
    }
}

}  // namespace
