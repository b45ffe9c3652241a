// umf-requester as outside benchmarks call it: `locate` prints one JSON line
// per frame, in the contract's key order, and keeps going past bad images.
#ifdef UMF_REQUESTER_TOOL

#include <gtest/gtest.h>
#include <sys/wait.h>
#include <unistd.h>

#include <array>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/videoio.hpp>
#include <random>
#include <sstream>
#include <string>
#include <vector>

#include "tests/detect/photo.hpp"

namespace fs = std::filesystem;
using Json = nlohmann::ordered_json;

namespace {

const std::string kField = std::string(UMF_DATA_DIR) + "/fields/b4-64x36.json";

struct Outcome {
    int code = -1;
    std::string out;  // stdout only: the JSON lines
    std::string err;
    std::vector<Json> lines;
};

// With `json`, every stdout line must be a JSON object (parse throws otherwise).
Outcome run(const std::string& args, const fs::path& dir, bool json = false) {
    const fs::path err_file = dir / "stderr.txt";
    const std::string cmd = std::string(UMF_REQUESTER_TOOL) + " " + args + " 2>" + err_file.string();
    Outcome r;
    FILE* p = popen(cmd.c_str(), "r");
    if (!p) return r;
    std::array<char, 4096> buf{};
    while (std::size_t n = fread(buf.data(), 1, buf.size(), p)) r.out.append(buf.data(), n);
    const int status = pclose(p);
    r.code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
    std::ifstream e(err_file);
    r.err.assign(std::istreambuf_iterator<char>(e), {});
    if (!json) return r;
    std::istringstream lines(r.out);
    for (std::string line; std::getline(lines, line);) r.lines.push_back(Json::parse(line));  // throws if not JSON
    return r;
}

std::vector<std::string> keys(const Json& j) {
    std::vector<std::string> k;
    for (const auto& item : j.items()) k.push_back(item.key());
    return k;
}

double distance(const Json& point, cv::Point2d truth) {
    return std::hypot(point[0].get<double>() - truth.x, point[1].get<double>() - truth.y);
}

// Photos are made once for the whole suite: the simulator is the slow part.
class Requester : public ::testing::Test {
protected:
    static void SetUpTestSuite() {
        shared_dir_ = fs::temp_directory_path() / ("umf_requester_" + std::to_string(::getpid()));
        fs::create_directories(shared_dir_);
        const umf::Field field = umf::test::shipped_field("b4-64x36.json");
        photo_ = new umf::test::Photo(umf::test::photograph_field(field, 0.5, 0, 0, 0, 300));
        const umf::test::Photo blank = umf::test::photograph_field(field, 0, 0, 0, 0, 300);
        ASSERT_TRUE(cv::imwrite(shared("photo.png"), photo_->shot.bgr));
        ASSERT_TRUE(cv::imwrite(shared("blank.png"), blank.shot.bgr));
    }
    static void TearDownTestSuite() {
        delete photo_;
        photo_ = nullptr;
        fs::remove_all(shared_dir_);
    }
    void SetUp() override {
        dir_ = shared_dir_ / ::testing::UnitTest::GetInstance()->current_test_info()->name();
        fs::create_directories(dir_);
    }

    static std::string shared(const std::string& name) { return (shared_dir_ / name).string(); }
    std::string path(const std::string& name) const { return (dir_ / name).string(); }
    Outcome locate(const std::string& args) const { return run("locate --field " + kField + " " + args, dir_, true); }
    static cv::Point2d truth(cv::Point2d image_px) {
        return umf::sim::image_to_field(photo_->shot, photo_->placement, image_px);
    }

    static inline fs::path shared_dir_;
    static inline umf::test::Photo* photo_ = nullptr;
    fs::path dir_;
};

TEST_F(Requester, LocatesAPhotoInTheContractsForm) {
    Outcome r = locate(shared("photo.png"));
    ASSERT_EQ(r.code, 0) << r.err;
    ASSERT_EQ(r.lines.size(), 1u) << r.out;
    const Json& j = r.lines[0];
    const std::vector<std::string> contract = {"frame", "found", "point", "H", "windows", "ms"};
    const std::vector<std::string> got = keys(j);
    ASSERT_GE(got.size(), contract.size()) << j.dump();
    EXPECT_EQ(std::vector<std::string>(got.begin(), got.begin() + contract.size()), contract) << j.dump();
    EXPECT_EQ(j["frame"], 0);
    ASSERT_EQ(j["found"], true) << j.dump();
    EXPECT_LT(distance(j["point"], truth({320, 240})), 0.2) << j.dump();
    ASSERT_TRUE(j["H"].is_array());
    ASSERT_EQ(j["H"].size(), 9u);
    for (const auto& x : j["H"]) EXPECT_TRUE(x.is_number());
    EXPECT_DOUBLE_EQ(j["H"][8].get<double>(), 1.0);
    // H takes the image centre to the point.
    const auto h = [&](int i) { return j["H"][i].get<double>(); };
    const double w = h(6) * 320 + h(7) * 240 + h(8);
    EXPECT_NEAR((h(0) * 320 + h(1) * 240 + h(2)) / w, j["point"][0].get<double>(), 1e-6);
    EXPECT_NEAR((h(3) * 320 + h(4) * 240 + h(5)) / w, j["point"][1].get<double>(), 1e-6);
    EXPECT_GE(j["windows"].get<int>(), 1);
    EXPECT_GT(j["ms"].get<double>(), 0);
    EXPECT_GT(j["confidence"].get<double>(), 0.5);
    EXPECT_FALSE(j.contains("state"));  // only with --sequence
}

TEST_F(Requester, UnreadableImagesGetAnErrorLineAndTheNextIsStillRead) {
    {
        std::ofstream corrupt(path("corrupt.png"), std::ios::binary);
        std::mt19937 rng(7);
        for (int i = 0; i < 5000; ++i) corrupt.put(static_cast<char>(rng() & 0xff));
    }
    Outcome r = locate(path("corrupt.png") + " " + path("missing.png") + " " + shared("photo.png"));
    ASSERT_EQ(r.code, 0) << r.err;
    ASSERT_EQ(r.lines.size(), 3u) << r.out;
    for (int i = 0; i < 3; ++i) EXPECT_EQ(r.lines[i]["frame"], i);
    for (int i = 0; i < 2; ++i) {
        const Json& j = r.lines[i];
        EXPECT_EQ(keys(j), (std::vector<std::string>{"frame", "found", "error"})) << j.dump();
        EXPECT_EQ(j["found"], false);
        EXPECT_EQ(j["error"].get<std::string>().rfind("cannot decode ", 0), 0u) << j.dump();
    }
    EXPECT_NE(r.lines[0]["error"].get<std::string>().find("corrupt.png"), std::string::npos);
    EXPECT_NE(r.lines[1]["error"].get<std::string>().find("no such file"), std::string::npos);
    EXPECT_EQ(r.lines[2]["found"], true) << r.lines[2].dump();
}

TEST_F(Requester, AScreenWithoutTheFieldIsNotFound) {
    Outcome r = locate(shared("blank.png"));
    ASSERT_EQ(r.code, 0) << r.err;
    ASSERT_EQ(r.lines.size(), 1u) << r.out;
    const Json& j = r.lines[0];
    EXPECT_EQ(keys(j), (std::vector<std::string>{"frame", "found", "ms", "reason"})) << j.dump();
    EXPECT_EQ(j["found"], false);
    EXPECT_FALSE(j["reason"].get<std::string>().empty());
}

TEST_F(Requester, AimMovesThePoint) {
    Outcome r = locate("--aim 100,80 " + shared("photo.png"));
    ASSERT_EQ(r.code, 0) << r.err;
    ASSERT_EQ(r.lines.size(), 1u) << r.out;
    ASSERT_EQ(r.lines[0]["found"], true) << r.out;
    EXPECT_LT(distance(r.lines[0]["point"], truth({100, 80})), 0.2) << r.out;
    EXPECT_GT(distance(r.lines[0]["point"], truth({320, 240})), 3) << r.out;
}

TEST_F(Requester, AVideoWithSequenceIsTracked) {
    const std::string video = path("clip.avi");
    {
        // OpenCV's own MJPEG writer: no codec library needed.
        cv::VideoWriter writer(video, cv::CAP_OPENCV_MJPEG, cv::VideoWriter::fourcc('M', 'J', 'P', 'G'), 10,
                               photo_->shot.bgr.size());
        ASSERT_TRUE(writer.isOpened());
        for (int i = 0; i < 5; ++i) writer.write(photo_->shot.bgr);
    }
    Outcome r = locate("--sequence --video " + video);
    ASSERT_EQ(r.code, 0) << r.err;
    ASSERT_EQ(r.lines.size(), 5u) << r.out;
    for (int i = 0; i < 5; ++i) {
        const Json& j = r.lines[i];
        EXPECT_EQ(j["frame"], i);
        ASSERT_TRUE(j.contains("state")) << j.dump();
        const std::string state = j["state"];
        EXPECT_TRUE(state == "locked" || state == "lost" || state == "searching") << state;
        EXPECT_EQ(j["found"].get<bool>(), state == "locked") << j.dump();
    }
    // The same picture five times: locked throughout, on the right point.
    for (const Json& j : r.lines) {
        ASSERT_EQ(j["state"], "locked") << j.dump();
        EXPECT_LT(distance(j["point"], truth({320, 240})), 0.2) << j.dump();
        EXPECT_EQ(keys(j)[3], "H");
    }

    Outcome plain = locate("--video " + video);
    ASSERT_EQ(plain.code, 0) << plain.err;
    ASSERT_EQ(plain.lines.size(), 5u) << plain.out;
    EXPECT_FALSE(plain.lines[0].contains("state"));
    EXPECT_EQ(plain.lines[4]["frame"], 4);
}

// Frames of a camera at rest before a web page whose field pulses between
// opacity 0.01 and 0.04 (sine, 1.5 s, 25 frames a second, from 0.3 s into
// its rise): once enough
// frames are kept, those the tracker has no lock on are found in the kept
// frames together, with and without the pulse announced.
TEST_F(Requester, AFaintPulseAtRestIsFoundInItsFramesTogether) {
    const umf::Field field = umf::test::shipped_field("b4-64x36.json");
    umf::test::Photo p;
    p.camera.resolution = {640, 480};
    p.pose.distance_mm = 300;
    p.pose.pitch_deg = 8;
    p.pose.roll_deg = 10;
    p.pose.aim_screen_px = {950, 520};
    const auto frames = umf::test::film_pulse(field, p, umf::sim::ScreenKind::web_page,
                                              umf::test::sine_pulse(0.01, 0.04, 1.5), 14, 0.3);
    std::string images;
    for (std::size_t i = 0; i < frames.size(); ++i) {
        const std::string name = path("frame" + std::to_string(100 + i) + ".png");
        ASSERT_TRUE(cv::imwrite(name, frames[i]));
        images += " " + name;
    }
    const cv::Point2d truth = umf::sim::image_to_field(p.shot, p.placement, {320, 240});
    for (const std::string announced :
         {"", "--pulse-period 1.5 --waveform sine ", "--pulse-period 1.5 --pulse-opacities 0.01,0.04 "}) {
        Outcome r = locate("--sequence " + announced + images);
        ASSERT_EQ(r.code, 0) << r.err;
        ASSERT_EQ(r.lines.size(), frames.size()) << r.out;
        int demodulated = 0;
        for (const Json& j : r.lines) {
            if (!j.value("demodulated", false)) continue;
            ++demodulated;
            EXPECT_TRUE(j["found"].get<bool>()) << j.dump();
            EXPECT_EQ(j["state"], "locked") << j.dump();
            EXPECT_GE(j["pulse_frames"].get<int>(), 8) << j.dump();
            EXPECT_GE(j["frame"].get<int>(), 7) << j.dump();
            EXPECT_LT(distance(j["point"], truth), 0.1) << announced << j.dump();
            EXPECT_EQ(keys(j)[3], "H");
        }
        // From the eighth frame on (the tracker may find some frames itself).
        int found = 0;
        for (std::size_t i = 7; i < r.lines.size(); ++i) found += r.lines[i]["found"].get<bool>();
        EXPECT_EQ(found, static_cast<int>(r.lines.size()) - 7) << announced << r.out;
        EXPECT_GT(demodulated, 0) << announced << r.out;
    }
}

TEST_F(Requester, WrongUsageExitsWithTwo) {
    EXPECT_EQ(run("", dir_).code, 2);
    Outcome unknown = run("frobnicate", dir_);
    EXPECT_EQ(unknown.code, 2);
    EXPECT_NE(unknown.err.find("usage:"), std::string::npos) << unknown.err;
    EXPECT_EQ(run("locate " + shared("photo.png"), dir_).code, 2);  // no --field
    EXPECT_EQ(locate("").code, 2);                                   // no frames
    EXPECT_EQ(locate("--video x.avi " + shared("photo.png")).code, 2);
    EXPECT_EQ(locate("--aim 10 " + shared("photo.png")).code, 2);
    EXPECT_EQ(locate("--aim 10,y " + shared("photo.png")).code, 2);
    EXPECT_EQ(locate("--sharpen " + shared("photo.png")).code, 2);
    EXPECT_EQ(locate("--field " + kField + " " + shared("photo.png")).code, 2);  // twice
    EXPECT_EQ(locate("--pulse-period 1.5 " + shared("photo.png")).code, 2);       // without --sequence
    EXPECT_EQ(locate("--sequence --pulse-period 0.1 " + shared("photo.png")).code, 2);
    EXPECT_EQ(locate("--sequence --pulse-period x " + shared("photo.png")).code, 2);
    EXPECT_EQ(locate("--sequence --waveform sine " + shared("photo.png")).code, 2);  // without a period
    EXPECT_EQ(locate("--sequence --pulse-period 1.5 --waveform square " + shared("photo.png")).code, 2);
    EXPECT_EQ(locate("--sequence --pulse-opacities 0.01,0.04 " + shared("photo.png")).code, 2);  // without a period
    EXPECT_EQ(locate("--sequence --pulse-period 1.5 --pulse-opacities 0.04,0.01 " + shared("photo.png")).code, 2);
    EXPECT_EQ(locate("--sequence --pulse-period 1.5 --pulse-opacities 0.01 " + shared("photo.png")).code, 2);
    for (const char* help : {"--help", "help", "locate --help", "help locate"}) {
        Outcome h = run(help, dir_);
        EXPECT_EQ(h.code, 0) << help;
        EXPECT_NE(h.out.find("exit codes"), std::string::npos) << help;
        EXPECT_NE(h.out.find("--sequence"), std::string::npos) << help;
    }
    EXPECT_EQ(run("help frobnicate", dir_).code, 2);
}

TEST_F(Requester, BadFieldOrVideoExitsWithThree) {
    std::ofstream(path("broken.json")) << "{\"format\": \"umf-field/1\", ";
    Outcome r = run("locate --field " + path("broken.json") + " " + shared("photo.png"), dir_);
    EXPECT_EQ(r.code, 3) << r.err;
    EXPECT_NE(r.err.find("broken.json"), std::string::npos) << r.err;
    EXPECT_TRUE(r.out.empty()) << r.out;
    EXPECT_EQ(run("locate --field " + path("missing.json") + " " + shared("photo.png"), dir_).code, 3);

    Outcome v = locate("--video " + path("missing.avi"));
    EXPECT_EQ(v.code, 3);
    EXPECT_NE(v.err.find("missing.avi"), std::string::npos) << v.err;
    std::ofstream(path("text.avi")) << "not a video";
    EXPECT_EQ(locate("--video " + path("text.avi")).code, 3);
}

}  // namespace

#endif  // UMF_REQUESTER_TOOL
