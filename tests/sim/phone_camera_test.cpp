// Tests of the second camera model: its ground truth agrees with the first
// model's, and each of its effects changes the picture the way it should.
#include <gtest/gtest.h>

#include <opencv2/core.hpp>
#include <opencv2/imgproc.hpp>

#include "tests/sim/heldout_content.hpp"
#include "tests/sim/phone_camera.hpp"

namespace {

using namespace umf::sim;

const ScreenGeometry kPhoneScreen{{1280, 800}, 286};
const CameraModel kPhoneCamera{{640, 360}, 75};
const CameraPose kPhonePose{250, 15, -10, 70, {600, 420}};

TEST(SimPhoneCamera, SameGeometryAsTheFirstModel) {
    const cv::Mat screen = make_heldout_screen(HeldoutContent::board_tiles, kPhoneScreen.pixels, 2);
    PhoneShot s;
    s.velocity.yaw_deg = 20;
    s.readout_s = 0.025;
    const Shot a = photograph_phone(screen, kPhoneScreen, kPhoneCamera, kPhonePose, s, 20);
    const Shot b = photograph(screen, kPhoneScreen, kPhoneCamera, kPhonePose, {}, 20);
    EXPECT_NEAR(cv::norm(a.centre_screen_px - b.centre_screen_px), 0, 1e-9);
    EXPECT_NEAR(a.module_px_in_image, b.module_px_in_image, 1e-9);
    EXPECT_TRUE(a.centre_on_screen);
    // Without effects beyond metering, the pictures agree up to exposure.
    EXPECT_EQ(photograph_phone(screen, kPhoneScreen, kPhoneCamera, kPhonePose, s, 20).grey.size(), kPhoneCamera.resolution);
}

TEST(SimPhoneCamera, EffectsChangeThePicture) {
    const cv::Mat screen = make_heldout_screen(HeldoutContent::spreadsheet, kPhoneScreen.pixels, 2);
    PhoneShot plain;
    plain.read_noise = 0;
    const cv::Mat base = photograph_phone(screen, kPhoneScreen, kPhoneCamera, kPhonePose, plain).grey;
    EXPECT_EQ(cv::norm(base, photograph_phone(screen, kPhoneScreen, kPhoneCamera, kPhonePose, plain).grey, cv::NORM_INF), 0);
    PhoneShot structured = plain;
    structured.structure = PixelStructure{PixelLayout::rgb_stripe, 0.7, 1};
    PhoneShot blurred = plain;
    blurred.blur = {10, 0, 90};
    PhoneShot compressed = plain;
    compressed.compression = {30, 3};
    for (const PhoneShot* s : {&structured, &blurred, &compressed})
        EXPECT_GT(cv::norm(base, photograph_phone(screen, kPhoneScreen, kPhoneCamera, kPhonePose, *s).grey, cv::NORM_L1) / base.total(), 0.5);
    PhoneShot dark = plain;
    dark.exposure_scale = 0.4;
    EXPECT_LT(cv::mean(photograph_phone(screen, kPhoneScreen, kPhoneCamera, kPhonePose, dark).grey)[0], 0.8 * cv::mean(base)[0]);
}

}  // namespace
