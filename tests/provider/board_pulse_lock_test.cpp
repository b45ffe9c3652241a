// The kiosk preset on the demo board, as a phone sees it: each tile filmed
// through the camera simulator at 25 frames a second for one whole period of
// the preset's pulse, straight on and at poses up to 30 degrees. A tile whose
// field is found at some phases and lost at others makes the Grab button
// blink: every frame is looked at on its own (the strictest reading, without
// the tracker's help), no miss may last longer than three frames, and no
// frame may be placed wrongly.
#ifdef UMF_PROVIDER_TESTS

#include <gtest/gtest.h>

#include <QImage>
#include <array>
#include <cmath>
#include <cstring>
#include <iostream>
#include <map>
#include <opencv2/core.hpp>
#include <opencv2/imgproc.hpp>

#include "provider/board/board.hpp"
#include "provider/screen/screen_field.hpp"
#include "provider/screen/screen_image.hpp"
#include "shared/detect/detector.hpp"
#include "shared/overlay/placement.hpp"
#include "shared/overlay/preset.hpp"
#include "shared/overlay/pulse.hpp"
#include "tests/provider/gui_test_app.hpp"
#include "tests/sim/camera.hpp"
#include "tests/sim/screen_source.hpp"
#include "tests/support/temp_dir.hpp"

namespace umf::provider {
namespace {

cv::Mat to_mat(const QImage& image) {
    const QImage rgb = image.convertToFormat(QImage::Format_RGB888);
    cv::Mat out(rgb.height(), rgb.width(), CV_8UC3);
    for (int y = 0; y < rgb.height(); ++y)
        std::memcpy(out.ptr(y), rgb.constScanLine(y), static_cast<std::size_t>(rgb.width()) * 3);
    cv::cvtColor(out, out, cv::COLOR_RGB2BGR);
    return out;
}

TEST(BoardPulseLock, EveryDemoTileStaysFoundThroughTheKioskPulse) {
    test::ensure_gui_application();
    test::TempDir dir;
    const Board board = write_demo_board(dir.path / "demo");
    const int width = 1920, height = 1080;
    const auto presets = overlay::built_in_presets();
    const overlay::Preset& kiosk = *overlay::find_preset(presets, "kiosk");
    // A virtual screen counts as 96 dpi, as the headless provider's does.
    const ScreenField field = screen_field_for(width, height, kiosk.module_px);
    const auto tiles = layout_board(board, width, height);
    const Detector detector(field.field);

    // One period at 25 fps; the screen at each frame's opacity, made once
    // per distinct opacity (the pulse repeats its values).
    constexpr double kFps = 25;
    const int frames = static_cast<int>(std::lround(kiosk.period_s * kFps));
    const sim::ScreenGeometry screen{{width, height}, 527};
    std::map<long, sim::ScreenSource> screens;
    std::vector<long> frame_opacity;
    for (int i = 0; i < frames; ++i) {
        const long key = std::lround(1000 * overlay::opacity_at(kiosk, i / kFps));
        frame_opacity.push_back(key);
        if (!screens.count(key))
            screens.try_emplace(key, to_mat(compose_screen(nullptr, &board, QSize(width, height), field, key / 1000.0, {})),
                                screen);
    }

    const sim::CameraModel camera{{640, 480}, 65};
    const std::vector<std::array<double, 3>> poses = {{0, 0, 0}, {20, 0, 0}, {0, -30, 0}, {-15, 20, 10}, {30, 10, -20}};
    int wrong = 0, found_frames = 0, all_frames = 0, longest_miss = 0;
    for (int t = 0; t < static_cast<int>(tiles.size()); ++t)
        for (const auto& [pitch, yaw, roll] : poses) {
            const PixelRect& r = tiles[static_cast<std::size_t>(t)];
            sim::CameraPose pose;
            pose.aim_screen_px = {r.x + r.width / 2.0, r.y + r.height / 2.0};
            pose.distance_mm = 330;  // the tile fills most of the view
            pose.pitch_deg = pitch;
            pose.yaw_deg = yaw;
            pose.roll_deg = roll;
            std::string row;
            int miss = 0, view_longest = 0;
            for (int i = 0; i < frames; ++i) {
                sim::Degradation d;
                d.defocus_sigma_px = 0.6;
                d.noise_sigma = 2;
                d.jpeg_quality = 85;
                d.seed = 100 * t + i;
                const sim::Shot shot = sim::photograph(screens.at(frame_opacity[i]), camera, pose, d);
                const Detection found = detector.detect(
                    GreyView{shot.grey.data, shot.grey.cols, shot.grey.rows, static_cast<int>(shot.grey.step)});
                double u = 0, v = 0;
                overlay::screen_to_field(field.placement, shot.centre_screen_px.x, shot.centre_screen_px.y, u, v);
                const bool right = found.found && std::hypot(found.aim_field.x() - u, found.aim_field.y() - v) < 0.5;
                wrong += found.found && !right;
                found_frames += right;
                ++all_frames;
                miss = right ? 0 : miss + 1;
                view_longest = std::max(view_longest, miss);
                row += right ? 'Y' : (found.found ? 'X' : '-');
            }
            longest_miss = std::max(longest_miss, view_longest);
            EXPECT_LE(view_longest, 3) << "tile " << t << " at pitch " << pitch << ", yaw " << yaw << ", roll " << roll
                                       << " lost the field for " << view_longest << " frames: " << row;
            if (view_longest > 0)
                std::cout << "[ lock     ] tile " << t << " pitch " << pitch << " yaw " << yaw << " roll " << roll << ": "
                          << row << "\n";
        }
    std::cout << "[ measure  ] kiosk pulse on the demo board, single frames at 640 x 480: " << found_frames << " of "
              << all_frames << " found, longest miss " << longest_miss << " frames\n";
    EXPECT_EQ(wrong, 0);
}

}  // namespace
}  // namespace umf::provider

#endif
