// The screen as the provider shows it: the board window, the field mixed in,
// `umf-provider compose` end to end, and the detector finding the field in a
// photograph of a composed board. Built only with the provider
// (UMF_PROVIDER_TESTS, see tests/CMakeLists.txt).
#ifdef UMF_PROVIDER_TESTS

#include <gtest/gtest.h>
#include <unistd.h>

#include <QColor>
#include <QImage>
#include <opencv2/imgcodecs.hpp>

#include <cmath>
#include <fstream>
#include <iterator>
#include <nlohmann/json.hpp>
#include <set>
#include <string>

#include "provider/board/board.hpp"
#include "provider/commands/compose_command.hpp"
#include "provider/screen/field_source.hpp"
#include "provider/screen/screen_field.hpp"
#include "provider/screen/screen_image.hpp"
#include "shared/detect/detector.hpp"
#include "shared/field/field_io.hpp"
#include "shared/overlay/field_mix.hpp"
#include "shared/overlay/preset.hpp"
#include "shared/overlay/pulse.hpp"
#include "tests/provider/gui_test_app.hpp"
#include "tests/sim/camera.hpp"

namespace {

namespace fs = std::filesystem;
using namespace umf;
using namespace umf::provider;

fs::path temp_dir(const std::string& name) {
    const fs::path dir = fs::temp_directory_path() / ("umf-screen-test-" + std::to_string(::getpid()) + "-" + name);
    fs::remove_all(dir);
    fs::create_directories(dir);
    return dir;
}

double luma(QRgb c) { return 0.299 * qRed(c) + 0.587 * qGreen(c) + 0.114 * qBlue(c); }

double mean_luma(const QImage& img, int cx, int cy, int radius) {
    double sum = 0;
    int n = 0;
    for (int y = cy - radius; y <= cy + radius; ++y)
        for (int x = cx - radius; x <= cx + radius; ++x, ++n) sum += luma(img.pixel(x, y));
    return sum / n;
}

class Screen : public ::testing::Test {
protected:
    void SetUp() override {
        test::ensure_gui_application();
        dir_ = temp_dir(::testing::UnitTest::GetInstance()->current_test_info()->name());
    }
    void TearDown() override { fs::remove_all(dir_); }
    fs::path dir_;
};

TEST_F(Screen, PaintedBoardShowsTilesAndTitle) {
    Board board = write_demo_board(dir_ / "demo");
    // A thumbnail that is missing and one that is not an image: placeholders, never a failure.
    board.items[0].thumbnail = dir_ / "missing.png";
    std::ofstream(dir_ / "broken.png") << "not a png";
    board.items[4].thumbnail = dir_ / "broken.png";
    const QSize screen(1920, 1080);
    const auto tiles = layout_board(board, screen.width(), screen.height());
    const QImage img = paint_board(board, tiles, screen);
    ASSERT_EQ(img.size(), screen);
    EXPECT_FALSE(img.hasAlphaChannel());

    const QRgb background = img.pixel(3, screen.height() - 3);
    for (std::size_t i = 0; i < tiles.size(); ++i) {
        const int cx = tiles[i].x + tiles[i].width / 2, cy = tiles[i].y + tiles[i].height / 2;
        EXPECT_GT(std::abs(mean_luma(img, cx, cy, 6) - luma(background)), 60) << "tile " << i;
        EXPECT_EQ(img.pixel(tiles[i].x + tiles[i].width / 2, tiles[i].y + tiles[i].height + 2), background)
            << "below tile " << i;
    }
    // Text in the title bar: many shades, not one fill.
    const int top = board_title_height(board, screen.height());
    std::set<QRgb> shades;
    for (int y = 0; y < top; ++y)
        for (int x = 0; x < screen.width() / 2; ++x) shades.insert(img.pixel(x, y));
    EXPECT_GT(shades.size(), 5u);
    // Text on each tile's upper part.
    for (std::size_t i = 0; i < tiles.size(); ++i) {
        std::set<QRgb> tile_shades;
        for (int y = tiles[i].y + tiles[i].height / 10; y < tiles[i].y + tiles[i].height / 4; ++y)
            for (int x = tiles[i].x + tiles[i].width / 10; x < tiles[i].x + tiles[i].width * 9 / 10; ++x)
                tile_shades.insert(img.pixel(x, y));
        EXPECT_GT(tile_shades.size(), 5u) << "tile " << i << " has no title drawn";
    }
    // The two kinds of items differ in colour (file: warm, URL: bluish).
    const auto corner = [&](std::size_t i) { return img.pixel(tiles[i].x + tiles[i].width / 2, tiles[i].y + 3); };
    EXPECT_NE(corner(0), corner(4));
    EXPECT_EQ(corner(0), corner(2));
    EXPECT_EQ(corner(4), corner(5));

    EXPECT_THROW(paint_board(board, {}, screen), std::invalid_argument);
    EXPECT_THROW(paint_board(board, tiles, QSize(0, 10)), std::invalid_argument);
}

TEST_F(Screen, LongTitlesAndTinyTilesNeverFail) {
    Board board;
    board.title = std::string(500, 'W');
    for (int i = 0; i < 40; ++i) {
        BoardItem item;
        item.title = "A rather long title that will need wrapping and then eliding " + std::string(200, 'x');
        item.url = "https://a-very-long-host-name.example.org/" + std::string(300, 'p');
        board.items.push_back(item);
    }
    board.items[3].rect = PixelRect{10, 10, 3, 3};
    for (QSize screen : {QSize(1920, 1080), QSize(320, 200), QSize(40, 30)}) {
        const QImage img = paint_board(board, layout_board(board, screen.width(), screen.height()), screen);
        EXPECT_EQ(img.size(), screen);
    }
}

TEST_F(Screen, ComposeAtOpacityZeroIsThePaintedBoard) {
    const Board board = write_demo_board(dir_ / "demo");
    const QSize screen(1280, 720);
    const ScreenField field = screen_field_for(screen.width(), screen.height());
    const QImage composed = compose_screen(nullptr, &board, screen, field, 0.0, {});
    const QImage painted = paint_board(board, layout_board(board, 1280, 720), screen).convertToFormat(QImage::Format_RGB888);
    EXPECT_EQ(composed.format(), QImage::Format_RGB888);
    EXPECT_TRUE(composed == painted);
}

TEST_F(Screen, ComposeMixesTheFieldIntoTheContent) {
    const QSize screen(1920, 1080);
    QImage content(screen, QImage::Format_RGB32);
    for (int y = 0; y < screen.height(); ++y)
        for (int x = 0; x < screen.width(); ++x)
            content.setPixel(x, y, qRgb((x * 7 + y) % 256, (y * 3) % 256, (x ^ y) % 256));
    const ScreenField field = screen_field_for(screen.width(), screen.height());
    for (const std::vector<std::string>& palette : {std::vector<std::string>{}, {"#ff8000", "#0040c0"}}) {
        const double a = 0.35;
        const QImage composed = compose_screen(&content, nullptr, screen, field, a, palette);
        const auto colours = overlay::field_colours_rgb(field.field, palette);
        int checked = 0;
        for (int i = 0; i < field.field.height; i += 3)
            for (int j = 0; j < field.field.width; j += 2) {
                const auto centre = overlay::field_to_screen(field.placement, j + 0.5, i + 0.5);
                const int x = static_cast<int>(centre.x), y = static_cast<int>(centre.y);
                const QRgb in = content.pixel(x, y), out = composed.pixel(x, y);
                const auto& c = colours[field.field.at(i, j)];
                ASSERT_EQ(qRed(out), std::lrint((1 - a) * qRed(in) + a * c[0])) << i << "," << j;
                ASSERT_EQ(qGreen(out), std::lrint((1 - a) * qGreen(in) + a * c[1])) << i << "," << j;
                ASSERT_EQ(qBlue(out), std::lrint((1 - a) * qBlue(in) + a * c[2])) << i << "," << j;
                ++checked;
            }
        EXPECT_GT(checked, 300);
    }
    // Black without content or board.
    const QImage black = compose_screen(nullptr, nullptr, screen, field, 0.0, {});
    EXPECT_EQ(black.pixel(100, 100), qRgb(0, 0, 0));
    const QImage wrong(QSize(800, 600), QImage::Format_RGB32);
    EXPECT_THROW(compose_screen(&wrong, nullptr, screen, field, 0.3, {}), std::invalid_argument);
    EXPECT_THROW(compose_screen(nullptr, nullptr, QSize(1280, 720), field, 0.3, {}), std::invalid_argument);
}

// --- umf-provider compose through run_compose

class Compose : public Screen {
protected:
    cli::Args args(std::map<std::string, std::string> named) const {
        cli::Args a;
        a.named = std::move(named);
        return a;
    }
    nlohmann::json read_json(const fs::path& p) const {
        std::ifstream in(p);
        return nlohmann::json::parse(in);
    }
    fs::path config() const { return dir_ / "config"; }
};

TEST_F(Compose, WritesTheScreenAndItsMap) {
    QImage content(QSize(1280, 720), QImage::Format_RGB32);
    content.fill(qRgb(230, 230, 225));
    ASSERT_TRUE(content.save(QString::fromStdString((dir_ / "content.png").string())));
    const fs::path out = dir_ / "out.png", map = dir_ / "map.json";
    ASSERT_EQ(run_compose(args({{"content", (dir_ / "content.png").string()}, {"preset", "balanced"},
                                {"time", "0.75"}, {"out", out.string()}, {"map", map.string()}}),
                          config()),
              0);
    const QImage shown(QString::fromStdString(out.string()));
    ASSERT_FALSE(shown.isNull());
    EXPECT_EQ(shown.size(), QSize(1280, 720));
    EXPECT_FALSE(shown.hasAlphaChannel());
    EXPECT_FALSE(shown.isGrayscale());

    const nlohmann::json m = read_json(map);
    const overlay::Preset balanced = *overlay::find_preset(overlay::built_in_presets(), "balanced");
    // The preset's module size, the field reaching past the smaller screen:
    // the screen's own, made from the seed compose kept in its configuration.
    ASSERT_TRUE(fs::is_regular_file(config() / "field-seed"));
    const ScreenField field = screen_field_for(1280, 720, balanced.module_px, own_field_source(config()));
    EXPECT_DOUBLE_EQ(field.placement.module_px, balanced.module_px);
    EXPECT_NE(field.field.modules, screen_field_for(1280, 720, balanced.module_px).field.modules);
    EXPECT_EQ(m["field"], fs::absolute(field.file).lexically_normal().string());
    EXPECT_TRUE(fs::is_regular_file(m["field"].get<std::string>()));
    EXPECT_EQ(m["field_id"], field.field.id);
    EXPECT_EQ(m["origin"], nlohmann::json({field.placement.origin_x, field.placement.origin_y}));
    EXPECT_EQ(m["module_px"], field.placement.module_px);
    EXPECT_DOUBLE_EQ(m["opacity"].get<double>(), overlay::opacity_at(balanced, 0.75));
    EXPECT_DOUBLE_EQ(m["opacity"].get<double>(), 0.4);  // half a period in: the pulse's peak
    EXPECT_EQ(m["screen"], nlohmann::json({1280, 720}));
    EXPECT_EQ(m["preset"], "balanced");
    EXPECT_EQ(m["time"], 0.75);
    EXPECT_FALSE(fs::exists(dir_ / "map.field.json"));

    // The image is the content with the field mixed in as compose_screen does it.
    const QImage expected = compose_screen(&content, nullptr, QSize(1280, 720), field, m["opacity"].get<double>(), {});
    EXPECT_TRUE(shown.convertToFormat(QImage::Format_RGB888) == expected);

    // --shipped-field: the field every screen shows, as it is shipped.
    cli::Args shipped = args({{"content", (dir_ / "content.png").string()}, {"preset", "balanced"},
                              {"time", "0.75"}, {"out", out.string()}, {"map", map.string()}});
    shipped.flags.push_back("shipped-field");
    ASSERT_EQ(run_compose(shipped, config()), 0);
    const ScreenField shipped_field = screen_field_for(1280, 720, balanced.module_px);
    EXPECT_EQ(read_json(map)["field"], fs::absolute(shipped_field.file).lexically_normal().string());
    EXPECT_EQ(read_json(map)["field_id"], shipped_field.field.id);
}

TEST_F(Compose, PortraitBoardGetsItsTurnedFieldWritten) {
    write_demo_board(dir_ / "demo");
    const fs::path map = dir_ / "portrait.json";
    ASSERT_EQ(run_compose(args({{"board", (dir_ / "demo" / "board.json").string()}, {"screen", "1080x1920"},
                                {"preset", "static"}, {"time", "0"}, {"out", (dir_ / "p.png").string()},
                                {"map", map.string()}}),
                          config()),
              0);
    const nlohmann::json m = read_json(map);
    EXPECT_EQ(m["field"], (dir_ / "portrait.field.json").string());
    const Field turned = load_field(m["field"].get<std::string>());
    EXPECT_EQ(turned.id, m["field_id"]);
    EXPECT_NE(turned.id.find("-r90"), std::string::npos);
    EXPECT_EQ(turned.height, screen_field_for(1080, 1920).field.height);
    EXPECT_EQ(m["screen"], nlohmann::json({1080, 1920}));
    EXPECT_EQ(QImage(QString::fromStdString((dir_ / "p.png").string())).size(), QSize(1080, 1920));
}

TEST_F(Compose, UserPresetsAndBadInput) {
    fs::create_directories(config());
    std::ofstream(config() / "presets.json")
        << R"([{"name": "mine", "opacity_min": 0.2, "opacity_max": 0.2, "period_s": 0, "palette": ["#102030", "#f0e0d0"]}])";
    const fs::path out = dir_ / "o.png", map = dir_ / "m.json";
    const auto base = [&](std::map<std::string, std::string> extra) {
        std::map<std::string, std::string> named = {
            {"screen", "640x360"}, {"preset", "mine"}, {"time", "3"}, {"out", out.string()}, {"map", map.string()}};
        for (auto& [k, v] : extra) named[k] = v;
        return args(named);
    };
    write_demo_board(dir_ / "demo");
    const std::string board = (dir_ / "demo" / "board.json").string();
    ASSERT_EQ(run_compose(base({{"board", board}}), config()), 0);
    EXPECT_DOUBLE_EQ(read_json(map)["opacity"].get<double>(), 0.2);
    EXPECT_EQ(read_json(map)["preset"], "mine");

    // Usage: unknown preset (the message lists the available ones), missing options, bad values.
    try {
        run_compose(base({{"board", board}, {"preset", "nope"}}), config());
        ADD_FAILURE();
    } catch (const cli::UsageError& e) {
        EXPECT_NE(std::string(e.what()).find("mine"), std::string::npos) << e.what();
        EXPECT_NE(std::string(e.what()).find("balanced"), std::string::npos) << e.what();
    }
    EXPECT_THROW(run_compose(base({}), config()), cli::UsageError);  // neither content nor board
    EXPECT_THROW(run_compose(base({{"board", board}, {"screen", "640by360"}}), config()), cli::UsageError);
    EXPECT_THROW(run_compose(base({{"board", board}, {"screen", "0x360"}}), config()), cli::UsageError);
    EXPECT_THROW(run_compose(base({{"board", board}, {"time", "soon"}}), config()), cli::UsageError);
    {
        std::vector<std::string> words = {"compose", "--board", board, "--colour", "red"};
        std::vector<char*> argv;
        for (auto& w : words) argv.push_back(w.data());
        EXPECT_THROW(cli::parse_args(static_cast<int>(argv.size()), argv.data(), 1, compose_options(), compose_flags()),
                     cli::UsageError);
    }
    cli::Args no_out = base({{"board", board}});
    no_out.named.erase("out");
    EXPECT_THROW(run_compose(no_out, config()), cli::UsageError);

    // Input: missing, corrupt, oversized content; a bad board; a bad presets file.
    EXPECT_EQ(run_compose(base({{"content", (dir_ / "missing.png").string()}}), config()), kComposeInputError);
    std::ofstream(dir_ / "corrupt.png") << "\x89PNG\r\n\x1a\n garbage";
    EXPECT_EQ(run_compose(base({{"content", (dir_ / "corrupt.png").string()}}), config()), kComposeInputError);
    QImage huge(QSize(16385, 1), QImage::Format_RGB32);
    huge.fill(Qt::white);
    ASSERT_TRUE(huge.save(QString::fromStdString((dir_ / "huge.png").string())));
    cli::Args huge_args = base({{"content", (dir_ / "huge.png").string()}});
    huge_args.named.erase("screen");
    EXPECT_EQ(run_compose(huge_args, config()), kComposeInputError);
    std::ofstream(dir_ / "bad-board.json") << R"({"format": "umf-board/1", "items": []})";
    EXPECT_EQ(run_compose(base({{"board", (dir_ / "bad-board.json").string()}}), config()), kComposeInputError);
    // Output: a folder that does not exist.
    EXPECT_EQ(run_compose(base({{"board", board}, {"out", (dir_ / "no" / "o.png").string()}}), config()),
              kComposeOutputError);
    std::ofstream(config() / "presets.json") << "[{\"name\": \"mine\", \"opacity_min\": 2}]";
    EXPECT_EQ(run_compose(base({{"board", board}}), config()), kComposeInputError);
}

// The point of compose: a camera pointed at the composed board finds the
// field, and the MAP's placement turns what it finds back into the screen
// point it aimed at.
TEST_F(Compose, DetectorFindsTheFieldOnTheComposedBoard) {
    fs::create_directories(config());
    std::ofstream(config() / "presets.json")
        << R"([{"name": "faint", "opacity_min": 0.3, "opacity_max": 0.3, "period_s": 0}])";
    const Board board = write_demo_board(dir_ / "demo");
    const fs::path out = dir_ / "screen.png", map = dir_ / "screen.json";
    ASSERT_EQ(run_compose(args({{"board", (dir_ / "demo" / "board.json").string()}, {"preset", "faint"},
                                {"time", "12.5"}, {"out", out.string()}, {"map", map.string()}}),
                          config()),
              0);
    const nlohmann::json m = read_json(map);
    ASSERT_EQ(m["opacity"], 0.3);
    ASSERT_EQ(m["screen"], nlohmann::json({1920, 1080}));
    const cv::Mat screen = cv::imread(out.string(), cv::IMREAD_COLOR);
    ASSERT_EQ(screen.cols, 1920);
    ASSERT_EQ(screen.rows, 1080);
    const Field field = load_field(m["field"].get<std::string>());
    const Detector detector(field);
    const overlay::FieldPlacement placement{m["origin"][0].get<double>(), m["origin"][1].get<double>(),
                                            m["module_px"].get<double>()};

    const auto tiles = layout_board(board, 1920, 1080);
    struct Aim {
        std::size_t tile;
        double pitch, yaw, roll;
    };
    for (const Aim aim : {Aim{0, 0, 0, 0}, Aim{4, 15, -10, 25}, Aim{2, -10, 20, 160}}) {
        const PixelRect& t = tiles[aim.tile];
        sim::CameraModel camera;
        camera.resolution = {640, 480};
        sim::CameraPose pose;
        pose.distance_mm = 300;
        pose.pitch_deg = aim.pitch;
        pose.yaw_deg = aim.yaw;
        pose.roll_deg = aim.roll;
        pose.aim_screen_px = {t.x + t.width / 2.0, t.y + t.height / 2.0};
        sim::Degradation degradation;
        degradation.noise_sigma = 2;
        const sim::Shot shot = sim::photograph(screen, sim::ScreenGeometry{}, camera, pose, degradation);
        const GreyView view{shot.grey.data, shot.grey.cols, shot.grey.rows, static_cast<std::ptrdiff_t>(shot.grey.step)};
        const Detection d = detector.detect(view);
        ASSERT_TRUE(d.found) << "tile " << aim.tile << ": " << d.failure;
        const overlay::PixelPoint found = overlay::field_to_screen(placement, d.aim_field.x(), d.aim_field.y());
        const double error_modules =
            std::hypot(found.x - pose.aim_screen_px.x, found.y - pose.aim_screen_px.y) / placement.module_px;
        EXPECT_LT(error_modules, 0.2) << "tile " << aim.tile << ": found (" << found.x << ", " << found.y
                                      << "), aimed at (" << pose.aim_screen_px.x << ", " << pose.aim_screen_px.y
                                      << ")";
        EXPECT_TRUE(t.contains(found.x, found.y)) << "tile " << aim.tile;
    }
}

}  // namespace

#endif  // UMF_PROVIDER_TESTS
