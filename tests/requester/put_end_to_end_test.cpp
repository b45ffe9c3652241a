// Screen to phone to screen on loopback: two headless providers run at the
// same time on their own ports; umf-requester grabs a file and a link from
// the first one's board (photographs of its screen by the camera simulator)
// and puts them on the second one's screen, where `umf-provider puts`
// answers the prompt as the person at that screen would. A file must arrive
// with the same bytes; a refused put, an upload cut halfway, a file above the
// screen's limit and a wrong token must leave nothing in its folder.
#if defined(UMF_PROVIDER_TESTS) && defined(UMF_REQUESTER_TOOL)

#include <gtest/gtest.h>
#include <signal.h>
#include <sys/stat.h>

#include <algorithm>
#include <chrono>
#include <filesystem>
#include <fstream>
#include <memory>
#include <nlohmann/json.hpp>
#include <opencv2/imgcodecs.hpp>
#include <sstream>
#include <string>
#include <thread>

#include "provider/board/board.hpp"
#include "tests/sim/camera.hpp"
#include "tests/support/files.hpp"
#include "tests/support/process.hpp"
#include "tests/support/temp_dir.hpp"

namespace {

namespace fs = std::filesystem;
using json = nlohmann::json;
using umf::test::ChildProcess;
using umf::test::run_command;
using umf::test::TempDir;
using umf::test::read_file;
using umf::test::seeded_bytes;
using umf::test::write_file;

std::vector<fs::path> paths_in(const fs::path& dir) {
    std::vector<fs::path> out;
    std::error_code ec;
    for (const auto& e : fs::directory_iterator(dir, ec)) out.push_back(e.path());
    return out;
}

std::string port_of(const std::string& url) {
    const auto colon = url.find(':', std::string("https://").size());
    const auto slash = url.find('/', colon);
    return url.substr(colon + 1, slash - colon - 1);
}

// A headless provider showing `board`, started with `extra` options.
struct RunningProvider {
    std::unique_ptr<ChildProcess> process;
    std::string url, port;
    cv::Mat screen;  // what it shows
    std::vector<umf::provider::PixelRect> tiles;
};

class PutEndToEnd : public ::testing::Test {
protected:
    static void SetUpTestSuite() {
        dir_ = new TempDir("umf-put-e2e");
        const fs::path d = dir_->path;
        // The phone's own configuration (its device name) stays in the test.
        fs::create_directories(d / "phone-config");
        fs::create_directories(d / "phone");
        fs::create_directories(d / "bin");
        // The desktop's xdg-open on screen B: records what it was asked to open.
        write_file(d / "bin" / "xdg-open", "#!/bin/sh\nprintf '%s\\n' \"$1\" >> '" + (d / "opened.txt").string() + "'\n");
        fs::permissions(d / "bin" / "xdg-open", fs::perms::owner_all);

        write_file(d / "report.pdf", seeded_bytes(7, 300'000));
        json board_a = {{"format", "umf-board/1"}, {"title", "Screen A"}, {"columns", 2}, {"items", json::array()}};
        board_a["items"].push_back({{"title", "Quarterly report"}, {"file", "report.pdf"}});
        board_a["items"].push_back({{"title", "Project site"}, {"url", "https://example.org/umf?from=a&n=1"}});
        write_file(d / "board-a.json", board_a.dump(2));
        json board_b = {{"format", "umf-board/1"}, {"title", "Screen B"}, {"columns", 1}, {"items", json::array()}};
        board_b["items"].push_back({{"title", "Drop things here"}, {"url", "https://example.org/wall"}});
        write_file(d / "board-b.json", board_b.dump(2));

        // A takes no puts; B asks, keeps files below 100 MB, and opens links
        // with the recording xdg-open.
        a_ = start("a", {"--puts", "never"});
        b_ = start("b", {"--puts", "ask", "--put-dir", (d / "b-puts").string(), "--put-max-mb", "100"});
    }

    static void TearDownTestSuite() {
        delete a_;
        delete b_;
        a_ = b_ = nullptr;
        delete dir_;
        dir_ = nullptr;
    }

    static RunningProvider* start(const std::string& name, const std::vector<std::string>& extra) {
        const fs::path d = dir_->path;
        auto* p = new RunningProvider;
        const std::string board = (d / ("board-" + name + ".json")).string();
        const std::string cfg = (d / ("cfg-" + name)).string();
        const fs::path screen_png = d / ("screen-" + name + ".png");
        const auto composed = run_command(std::string(UMF_PROVIDER_TOOL) + " compose --board " + board +
                                          " --screen 1920x1080 --preset kiosk --time 0.75 --out " +
                                          screen_png.string() + " --map " + (d / "map.json").string() +
                                          " --config-dir " + cfg);
        EXPECT_EQ(composed.exit_code, 0) << composed.out;
        p->screen = cv::imread(screen_png.string(), cv::IMREAD_COLOR);
        p->tiles = umf::provider::layout_board(umf::provider::load_board(board), 1920, 1080);
        std::vector<std::string> argv = {"/usr/bin/env",  "PATH=" + (d / "bin").string() + ":" + std::getenv("PATH"),
                                         UMF_PROVIDER_TOOL, "--headless", "--board", board, "--port", "0",
                                         "--screen", "1920x1080", "--config-dir", cfg, "--no-qr"};
        argv.insert(argv.end(), extra.begin(), extra.end());
        p->process = std::make_unique<ChildProcess>(argv);
        const auto line = p->process->read_until([](const std::string& l) { return l.rfind("pairing URL: ", 0) == 0; });
        EXPECT_TRUE(line) << "provider " << name << " printed no pairing URL:\n" << p->process->output();
        if (line) p->url = line->substr(std::string("pairing URL: ").size());
        p->port = port_of(p->url);
        return p;
    }

    // A phone photo of `p`'s screen aimed at (x, y).
    static fs::path photo(const RunningProvider& p, double x, double y, const std::string& name, double yaw = 8) {
        umf::sim::CameraPose pose;
        pose.distance_mm = 350;
        pose.yaw_deg = yaw;
        pose.pitch_deg = 6;
        pose.aim_screen_px = {x, y};
        umf::sim::Degradation degradation;
        degradation.noise_sigma = 2;
        degradation.jpeg_quality = 90;
        degradation.seed = 5;
        const auto shot = umf::sim::photograph(p.screen, {{1920, 1080}, 527}, {{1280, 720}, 65}, pose, degradation);
        const fs::path file = dir_->path / (name + ".png");
        cv::imwrite(file.string(), shot.bgr);
        return file;
    }
    static fs::path photo_of_tile(const RunningProvider& p, std::size_t tile, const std::string& name) {
        const auto& t = p.tiles.at(tile);
        return photo(p, t.x + t.width / 2.0, t.y + t.height / 2.0, name, -10);
    }

    static std::vector<std::string> requester(const std::vector<std::string>& args) {
        std::vector<std::string> argv = {"/usr/bin/env", "XDG_CONFIG_HOME=" + (dir_->path / "phone-config").string(),
                                         "DISPLAY=", "WAYLAND_DISPLAY=", UMF_REQUESTER_TOOL};
        argv.insert(argv.end(), args.begin(), args.end());
        return argv;
    }

    // Runs the requester to its end: its JSON line and exit code.
    static std::pair<json, int> run_requester(const std::vector<std::string>& args) {
        ChildProcess phone(requester(args));
        const int code = phone.wait(std::chrono::seconds(90));
        const std::string out = phone.output();
        return {json::parse(out.substr(0, out.find('\n')), nullptr, false), code};
    }

    // The first put waiting at `p`, as `umf-provider puts --json` lists it
    // (waits up to 20 s for one to appear).
    static json waiting_put(const RunningProvider& p) {
        const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(20);
        while (std::chrono::steady_clock::now() < deadline) {
            const auto r = run_command(std::string(UMF_PROVIDER_TOOL) + " puts --json --port " + p.port);
            const json list = json::parse(r.out, nullptr, false);
            if (list.is_object() && list.contains("puts") && !list["puts"].empty()) return list["puts"][0];
            std::this_thread::sleep_for(std::chrono::milliseconds(100));
        }
        return json();
    }

    static int answer(const RunningProvider& p, const json& put, const std::string& how) {
        return run_command(std::string(UMF_PROVIDER_TOOL) + " puts " + how + " " +
                           std::to_string(put.value("id", 0)) + " --port " + p.port + " >/dev/null")
            .exit_code;
    }

    // Grabs what tile `tile` of screen A shows into the phone's folder.
    static json grab_from_a(std::size_t tile) {
        const auto [line, code] = run_requester({"grab", "--url", a_->url, "--image",
                                                 photo_of_tile(*a_, tile, "a-" + std::to_string(tile)).string(),
                                                 "--out", (dir_->path / "phone").string()});
        EXPECT_EQ(code, 0) << line.dump();
        return line;
    }

    static fs::path b_folder() { return dir_->path / "b-puts"; }

    static inline TempDir* dir_ = nullptr;
    static inline RunningProvider* a_ = nullptr;
    static inline RunningProvider* b_ = nullptr;
};

TEST_F(PutEndToEnd, AFileGrabbedFromOneScreenIsPutOnAnotherWithTheSameBytes) {
    const json grabbed = grab_from_a(0);
    ASSERT_EQ(grabbed.value("ok", false), true) << grabbed.dump();
    const fs::path carried = grabbed.value("saved", "");
    ASSERT_EQ(read_file(carried), read_file(dir_->path / "report.pdf"));

    ChildProcess phone(requester({"put", carried.string(), "--url", b_->url, "--title", "From screen A", "--image",
                                  photo(*b_, 700, 600, "b-file").string()}));
    const json put = waiting_put(*b_);
    ASSERT_FALSE(put.is_null()) << "no put waited for an answer at screen B";
    EXPECT_EQ(put.value("name", ""), "report.pdf") << put.dump();
    EXPECT_EQ(put.value("size", 0), 300'000) << put.dump();
    ASSERT_EQ(answer(*b_, put, "--accept"), 0);
    const int code = phone.wait();
    const json line = json::parse(phone.output().substr(0, phone.output().find('\n')), nullptr, false);
    ASSERT_EQ(code, 0) << phone.output();
    EXPECT_EQ(line.value("outcome", ""), "saved") << line.dump();
    EXPECT_EQ(line.value("kind", ""), "file");
    EXPECT_EQ(line.value("sha256", ""), grabbed.value("sha256", "x"));
    const std::string name = line.value("name", "");
    ASSERT_FALSE(name.empty()) << line.dump();
    EXPECT_EQ(read_file(b_folder() / name), read_file(dir_->path / "report.pdf")) << "the file arrived changed";

    // Put again: a second name beside the first, which stays as it was.
    ChildProcess again(requester({"put", carried.string(), "--url", b_->url, "--image",
                                  photo(*b_, 1300, 500, "b-file-2", -6).string()}));
    const json second = waiting_put(*b_);
    ASSERT_FALSE(second.is_null());
    ASSERT_EQ(answer(*b_, second, "--accept"), 0);
    ASSERT_EQ(again.wait(), 0) << again.output();
    EXPECT_NE(again.output().find("\"name\":\"report (1).pdf\""), std::string::npos) << again.output();
    EXPECT_EQ(read_file(b_folder() / "report (1).pdf"), read_file(dir_->path / "report.pdf"));
    EXPECT_EQ(read_file(b_folder() / name), read_file(dir_->path / "report.pdf"));
}

TEST_F(PutEndToEnd, ALinkGrabbedFromOneScreenOpensOnAnother) {
    const json grabbed = grab_from_a(1);
    ASSERT_EQ(grabbed.value("kind", ""), "url") << grabbed.dump();
    const std::string link = grabbed.value("url", "");
    ASSERT_EQ(link, "https://example.org/umf?from=a&n=1");

    ChildProcess phone(requester({"put", link, "--url", b_->url, "--image", photo(*b_, 960, 540, "b-url").string()}));
    const json put = waiting_put(*b_);
    ASSERT_FALSE(put.is_null());
    EXPECT_EQ(put.value("url", ""), link) << put.dump();
    ASSERT_EQ(answer(*b_, put, "--accept"), 0);
    ASSERT_EQ(phone.wait(), 0) << phone.output();
    EXPECT_NE(phone.output().find("\"outcome\":\"opened\""), std::string::npos) << phone.output();
    // xdg-open runs on its own after the answer; give it a moment.
    for (int i = 0; i < 50 && read_file(dir_->path / "opened.txt").find(link) == std::string::npos; ++i)
        std::this_thread::sleep_for(std::chrono::milliseconds(100));
    EXPECT_NE(read_file(dir_->path / "opened.txt").find(link + "\n"), std::string::npos);
}

TEST_F(PutEndToEnd, ADismissedPutLeavesNothing) {
    const auto before = paths_in(b_folder());
    write_file(dir_->path / "phone" / "holiday.jpg", seeded_bytes(11, 40'000));
    ChildProcess phone(requester({"put", (dir_->path / "phone" / "holiday.jpg").string(), "--url", b_->url,
                                  "--image", photo(*b_, 900, 700, "b-dismiss").string()}));
    const json put = waiting_put(*b_);
    ASSERT_FALSE(put.is_null());
    ASSERT_EQ(answer(*b_, put, "--dismiss"), 0);
    EXPECT_EQ(phone.wait(), 5) << phone.output();
    EXPECT_NE(phone.output().find("\"code\":\"refused\""), std::string::npos) << phone.output();
    EXPECT_EQ(paths_in(b_folder()), before);
}

// A phone that dies mid-upload leaves only the hidden temporary file, which
// waits for the rest for the link's lifetime (PutServer tests its end):
// nothing appears under a real name.
TEST_F(PutEndToEnd, AnUploadCutHalfwayLeavesNothingUnderARealName) {
    const auto before = paths_in(b_folder());
    const fs::path big = dir_->path / "phone" / "recording.webm";
    write_file(big, seeded_bytes(13, 60'000'000));
    ChildProcess phone(requester({"put", big.string(), "--url", b_->url, "--image",
                                  photo(*b_, 1000, 600, "b-cut").string()}));
    const json put = waiting_put(*b_);
    ASSERT_FALSE(put.is_null());
    ASSERT_EQ(answer(*b_, put, "--accept"), 0);
    // Stop the phone as soon as bytes arrive, then end it: the connection
    // breaks with part of the file on the screen's side.
    bool stopped = false;
    std::uintmax_t arrived = 0;
    const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(20);
    while (!stopped && std::chrono::steady_clock::now() < deadline) {
        for (const auto& f : paths_in(b_folder())) {
            if (std::find(before.begin(), before.end(), f) != before.end()) continue;
            std::error_code ec;
            const auto size = fs::file_size(f, ec);
            if (!ec && size > 0) {
                ::kill(phone.pid(), SIGSTOP);
                stopped = true;
                std::this_thread::sleep_for(std::chrono::milliseconds(200));
                arrived = fs::file_size(f, ec);
                break;
            }
        }
        if (!stopped) std::this_thread::sleep_for(std::chrono::milliseconds(1));
    }
    ASSERT_TRUE(stopped) << "no upload began:\n" << phone.output();
    EXPECT_LT(arrived, 60'000'000u) << "the whole file had arrived before the cut";
    ::kill(phone.pid(), SIGKILL);
    EXPECT_EQ(phone.wait(), -1);
    std::this_thread::sleep_for(std::chrono::milliseconds(300));
    for (const auto& f : paths_in(b_folder()))
        if (std::find(before.begin(), before.end(), f) == before.end()) {
            EXPECT_EQ(f.filename().string().rfind(".umf-put-", 0), 0u) << f << " appeared under a real name";
        }
}

TEST_F(PutEndToEnd, AFileAboveTheScreensLimitIsRefusedBeforeAnyoneIsAsked) {
    const auto before = paths_in(b_folder());
    const fs::path big = dir_->path / "phone" / "too-big.bin";
    {
        std::ofstream out(big, std::ios::binary);
        out.seekp(100'000'001 - 1);
        out.put('\0');  // sparse: 100 MB and a byte, above B's --put-max-mb 100
    }
    const auto [line, code] = run_requester({"put", big.string(), "--url", b_->url, "--image",
                                             photo(*b_, 960, 400, "b-big").string()});
    EXPECT_EQ(code, 5) << line.dump();
    EXPECT_EQ(line["error"].value("code", ""), "too_large") << line.dump();
    EXPECT_EQ(paths_in(b_folder()), before);
}

TEST_F(PutEndToEnd, AWrongTokenIsRefusedAndAScreenWithoutPutsSaysSo) {
    std::string wrong = b_->url;
    const auto t = wrong.find("#t=") + 3;
    wrong[t] = wrong[t] == 'A' ? 'B' : 'A';
    write_file(dir_->path / "phone" / "note.txt", "a note\n");
    const auto before = paths_in(b_folder());
    const auto [line, code] = run_requester({"put", (dir_->path / "phone" / "note.txt").string(), "--url", wrong,
                                             "--image", photo(*b_, 960, 540, "b-token").string()});
    EXPECT_EQ(code, 4) << line.dump();
    EXPECT_EQ(line["error"].value("code", ""), "unauthorized") << line.dump();
    EXPECT_EQ(paths_in(b_folder()), before);

    const auto [no_puts, no_puts_code] = run_requester({"put", "https://example.org/x", "--url", a_->url, "--image",
                                                        photo_of_tile(*a_, 0, "a-no-puts").string()});
    EXPECT_EQ(no_puts_code, 5) << no_puts.dump();
    EXPECT_EQ(no_puts["error"].value("code", ""), "no_puts") << no_puts.dump();
}

}  // namespace

#endif
