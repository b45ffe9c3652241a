// The whole product on loopback: a headless provider showing a board of six
// items, the screen it shows (umf-provider compose) photographed by the
// camera simulator aimed at each item, and umf-requester grab taking what is
// there. Every file must arrive with the same bytes, every URL as it is on the
// board, and a second grab of a file must not overwrite the first.
#if defined(UMF_PROVIDER_TESTS) && defined(UMF_REQUESTER_TOOL)

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <opencv2/imgcodecs.hpp>
#include <sstream>
#include <string>

#include "provider/board/board.hpp"
#include "tests/sim/camera.hpp"
#include "tests/support/files.hpp"
#include "tests/support/process.hpp"
#include "tests/support/temp_dir.hpp"

namespace {

using umf::test::TempDir;

namespace fs = std::filesystem;
using json = nlohmann::json;
using umf::test::ChildProcess;
using umf::test::read_file;
using umf::test::run_command;
using umf::test::seeded_bytes;
using umf::test::write_file;

class GrabEndToEnd : public ::testing::Test {
protected:
    TempDir dir;
    fs::path board_file;
    json board_json;

    void SetUp() override {
        // Four files of different kinds and sizes, two URLs, in a 3 x 2 grid.
        const std::vector<std::pair<std::string, std::size_t>> files = {
            {"notes.txt", 700}, {"diagram.png", 50'000}, {"report.pdf", 300'000}, {"table.csv", 1}};
        board_json = {{"format", "umf-board/1"}, {"title", "End-to-end board"}, {"columns", 3}, {"items", json::array()}};
        for (std::size_t i = 0; i < files.size(); ++i) {
            write_file(dir.path / files[i].first, seeded_bytes(2463534242u + static_cast<std::uint32_t>(i), files[i].second));
            board_json["items"].push_back({{"title", "Item " + std::to_string(i)}, {"file", files[i].first}});
        }
        board_json["items"].push_back({{"title", "Project site"}, {"url", "https://example.org/umf?a=1&b=2"}});
        board_json["items"].push_back({{"title", "Specification"}, {"url", "https://www.w3.org/TR/websockets/"}});
        board_file = dir.path / "board.json";
        write_file(board_file, board_json.dump(2));
    }
};

TEST_F(GrabEndToEnd, EveryBoardItemArrivesIntactAndNothingIsOverwritten) {
    // The screen the provider shows, and where the field lies on it.
    const fs::path screen_png = dir.path / "screen.png", map_file = dir.path / "map.json";
    const auto composed = run_command(std::string(UMF_PROVIDER_TOOL) + " compose --board " + board_file.string() +
                                      " --screen 1920x1080 --preset kiosk --time 0.75 --out " + screen_png.string() +
                                      " --map " + map_file.string() + " --config-dir " + (dir.path / "cfg").string());
    ASSERT_EQ(composed.exit_code, 0) << composed.out;
    const cv::Mat screen = cv::imread(screen_png.string(), cv::IMREAD_COLOR);
    ASSERT_EQ(screen.cols, 1920);
    ASSERT_EQ(screen.rows, 1080);

    ChildProcess provider({UMF_PROVIDER_TOOL, "--headless", "--board", board_file.string(), "--port", "0",
                           "--screen", "1920x1080", "--config-dir", (dir.path / "cfg").string(), "--no-qr"});
    const auto url_line = provider.read_until([](const std::string& l) { return l.rfind("pairing URL: ", 0) == 0; });
    ASSERT_TRUE(url_line) << "the provider printed no pairing URL:\n" << provider.output();
    const std::string url = url_line->substr(std::string("pairing URL: ").size());

    const umf::provider::Board board = umf::provider::load_board(board_file);
    const auto tiles = umf::provider::layout_board(board, 1920, 1080);
    const fs::path out_dir = dir.path / "received";
    fs::create_directories(out_dir);

    auto grab_at = [&](std::size_t item, double yaw) {
        const auto& t = tiles[item];
        umf::sim::CameraPose pose;
        pose.distance_mm = 350;
        pose.yaw_deg = yaw;
        pose.pitch_deg = 8;
        pose.aim_screen_px = {t.x + t.width / 2.0, t.y + t.height / 2.0};
        umf::sim::Degradation degradation;
        degradation.noise_sigma = 2;
        degradation.jpeg_quality = 90;
        degradation.seed = 17 + item;
        const auto shot = umf::sim::photograph(screen, {{1920, 1080}, 527}, {{1280, 720}, 65}, pose, degradation);
        const fs::path shot_png = dir.path / ("shot-" + std::to_string(item) + ".png");
        cv::imwrite(shot_png.string(), shot.bgr);
        const auto r = run_command(std::string(UMF_REQUESTER_TOOL) + " grab --url '" + url + "' --image " +
                                   shot_png.string() + " --out " + out_dir.string());
        EXPECT_EQ(r.exit_code, 0) << "item " << item << ": " << r.out;
        return json::parse(r.out.empty() ? "{}" : r.out.substr(0, r.out.find('\n')), nullptr, false);
    };

    for (std::size_t i = 0; i < board.items.size(); ++i) {
        const json result = grab_at(i, i % 2 ? 15.0 : -10.0);
        ASSERT_TRUE(result.is_object()) << "item " << i;
        ASSERT_EQ(result.value("ok", false), true) << "item " << i << ": " << result.dump();
        EXPECT_EQ(result.value("title", ""), board.items[i].title);
        if (board.items[i].file) {
            EXPECT_EQ(result.value("kind", ""), "file");
            const fs::path saved = result.value("saved", "");
            EXPECT_EQ(saved.parent_path(), out_dir);
            EXPECT_EQ(saved.filename(), board.items[i].file->filename());
            EXPECT_EQ(read_file(saved), read_file(*board.items[i].file)) << "item " << i << " arrived changed";
        } else {
            EXPECT_EQ(result.value("kind", ""), "url");
            EXPECT_EQ(result.value("url", ""), *board.items[i].url);
        }
    }

    // The same file again: a new name beside the first, which stays as it was.
    const json again = grab_at(2, 5.0);
    ASSERT_EQ(again.value("ok", false), true) << again.dump();
    EXPECT_EQ(fs::path(again.value("saved", "")).filename(), "report (1).pdf");
    EXPECT_EQ(read_file(out_dir / "report.pdf"), read_file(dir.path / "report.pdf"));
    EXPECT_EQ(read_file(out_dir / "report (1).pdf"), read_file(dir.path / "report.pdf"));

    // Nothing else landed in the folder: no partial or temporary files.
    std::size_t files = 0;
    for (const auto& e : fs::directory_iterator(out_dir)) files += e.is_regular_file();
    EXPECT_EQ(files, 5u);
    EXPECT_EQ(provider.stop(), 0) << provider.output();
}

}  // namespace

#endif
