// The board shown for real: a frame of the board window is the composed
// screen (within rounding), and under an X server (Xvfb) the provider's
// full-screen board carries a field the detector finds at the right place,
// pulsing.
#ifdef UMF_PROVIDER_TESTS

#include <gtest/gtest.h>

#include <QPainter>
#include <cstdlib>
#include <filesystem>
#include <fstream>

#include "provider/board/board.hpp"
#include "provider/desktop/x11/x11_desktop.hpp"
#include "provider/screen/board_window.hpp"
#include "provider/screen/field_source.hpp"
#include "provider/screen/screen_field.hpp"
#include "provider/screen/screen_image.hpp"
#include "shared/detect/detector.hpp"
#include "shared/overlay/preset.hpp"
#include "tests/provider/gui_test_app.hpp"
#include "tests/support/temp_dir.hpp"
#include "tests/support/x11_session.hpp"

namespace {

namespace fs = std::filesystem;
using namespace umf::provider;
using namespace umf::test;

Board two_item_board(const fs::path& dir) {
    std::ofstream(dir / "a.txt") << "a";
    Board board;
    board.title = "Window test";
    board.items.push_back({"Notes", dir / "a.txt", std::nullopt, std::nullopt, std::nullopt});
    board.items.push_back({"Site", std::nullopt, "https://example.org/", std::nullopt, std::nullopt});
    return board;
}

// For a failure's message: the screen as the test saw it, kept in /tmp.
std::string save_pgm(const std::vector<std::uint8_t>& grey, const fs::path&) {
    const fs::path out = fs::temp_directory_path() / "umf-board-window-screen.pgm";
    std::ofstream f(out, std::ios::binary);
    f << "P5 1920 1080 255\n";
    f.write(reinterpret_cast<const char*>(grey.data()), static_cast<std::streamsize>(grey.size()));
    return "the screen: " + out.string();
}

TEST(BoardWindow, AFrameIsTheComposedScreen) {
    ensure_gui_application();
    TempDir dir;
    const Board board = two_item_board(dir.path);
    const QSize size(1280, 720);
    const ScreenField field = screen_field_for(size.width(), size.height());
    const QImage painted = paint_board(board, layout_board(board, size.width(), size.height()), size);
    const QImage layer = field_layer(field, {});

    for (double opacity : {0.0, 0.3, 1.0}) {
        QImage frame(size, QImage::Format_RGB32);
        QPainter painter(&frame);
        paint_board_frame(painter, painted, layer, opacity);
        painter.end();
        const QImage composed =
            compose_screen(nullptr, &board, size, field, opacity, {}).convertToFormat(QImage::Format_RGB32);
        int worst = 0;
        for (int y = 0; y < size.height(); ++y)
            for (int x = 0; x < size.width(); ++x) {
                const QRgb a = frame.pixel(x, y), b = composed.pixel(x, y);
                worst = std::max({worst, std::abs(qRed(a) - qRed(b)), std::abs(qGreen(a) - qGreen(b)),
                                  std::abs(qBlue(a) - qBlue(b))});
            }
        // QPainter's opacity has 256 steps.
        EXPECT_LE(worst, 2) << "opacity " << opacity;
    }
}

TEST(BoardWindow, TheProvidersBoardOnAnXServerCarriesThePulsingField) {
    for (const char* program : {"Xvfb"})
        if (!find_program(program)) GTEST_SKIP() << program << " is not installed (Debian: apt-get install xvfb)";
    TempDir dir;
    const Board board = two_item_board(dir.path);
    std::ofstream(dir.path / "board.json") << board_to_json(board, dir.path);
    const XServer server = start_xvfb(dir.path / "xvfb.log", "1920x1080x24");

    Process::Options options;
    options.cwd = dir.path;
    options.env = environment_with({{"DISPLAY", server.display}, {"QT_QPA_PLATFORM", "xcb"}});
    options.log = dir.path / "provider.log";
    Process provider({UMF_PROVIDER_TOOL, "--board", (dir.path / "board.json").string(), "--port", "0", "--no-qr",
                      "--config-dir", (dir.path / "cfg").string(), "--preset", "kiosk"},
                     options);
    auto log = [&] {
        std::ifstream in(dir.path / "provider.log");
        return std::string(std::istreambuf_iterator<char>(in), {});
    };
    ASSERT_TRUE(wait_until([&] { return log().find("pairing URL") != std::string::npos; }, 20s)) << log();

    const auto desktop = std::make_shared<const X11Desktop>(server.display);
    const ScreenField field = screen_field_for(1920, 1080, 0.0, own_field_source(dir.path / "cfg"));  // what it shows
    const umf::Detector detector(field.field);
    auto capture_grey = [&](std::vector<std::uint8_t>& grey) {
        const Capture shot = desktop->capture({0, 0, 1920, 1080});
        grey.resize(shot.pixels.size());
        for (std::size_t i = 0; i < grey.size(); ++i) {
            const std::uint32_t p = shot.pixels[i];
            grey[i] = static_cast<std::uint8_t>((((p >> 16) & 255) * 77 + ((p >> 8) & 255) * 150 + (p & 255) * 29) >> 8);
        }
    };
    // The window maps and paints: wait until the field is there.
    std::vector<std::uint8_t> grey, later;
    umf::Detection found;
    ASSERT_TRUE(wait_until(
        [&] {
            capture_grey(grey);
            found = detector.detect(umf::GreyView{grey.data(), 1920, 1080, 1920});
            return found.found;
        },
        20s))
        << "no field on the screen: " << found.failure << "\n" << log() << save_pgm(grey, dir.path);
    // The image centre is screen pixel (960, 540): field point (32, 18) under the placement.
    double u = 0, v = 0;
    umf::overlay::screen_to_field(field.placement, 960, 540, u, v);
    EXPECT_NEAR(found.aim_field.x(), u, 0.05);
    EXPECT_NEAR(found.aim_field.y(), v, 0.05);

    // A third of the kiosk preset's 1.5 s period later the screen differs: it pulses.
    std::this_thread::sleep_for(std::chrono::milliseconds(500));
    capture_grey(later);
    long differing = 0;
    for (std::size_t i = 0; i < grey.size(); ++i) differing += std::abs(grey[i] - later[i]) > 4;
    EXPECT_GT(differing, 100000) << "the field does not pulse";

    ::kill(provider.pid(), SIGTERM);
    const auto status = provider.wait_exit(10s);
    ASSERT_TRUE(status) << "the provider did not stop";
    EXPECT_EQ(*status, 0) << log();
}

}  // namespace

#endif
