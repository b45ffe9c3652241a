// umf-requester grab through its program, against the real provider server
// (connect, pinning, hello, detection, aim, grab: today it answers every
// grab with "none") and against a scripted stand-in (tests/requester/
// fake_provider.hpp) for links, downloads and their failures.
#if defined(UMF_PROVIDER_TESTS) && defined(UMF_REQUESTER_TOOL)

#include <gtest/gtest.h>
#include <openssl/evp.h>
#include <stdlib.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <memory>
#include <nlohmann/json.hpp>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/videoio.hpp>
#include <sstream>
#include <string>
#include <vector>

#include "provider/service/pairing.hpp"
#include "provider/service/service.hpp"
#include "provider/service/service_server.hpp"
#include "provider/trust/tls_identity_store.hpp"
#include "tests/detect/photo.hpp"
#include "tests/requester/fake_provider.hpp"
#include "tests/support/files.hpp"
#include "tests/support/process.hpp"

namespace {

namespace fs = std::filesystem;
using umf::test::read_file;
using umf::test::shell_quoted;
using Json = nlohmann::ordered_json;
using namespace umf::provider;

struct Result {
    int code = -1;
    std::string out;
    std::string err;
    Json line;  // the one JSON line on stdout
    double seconds = 0;
};

// Runs umf-requester with `args`; stdout must be exactly one JSON line.
Result run(const std::string& args, const fs::path& dir, const std::string& env = "DISPLAY= WAYLAND_DISPLAY=") {
    const fs::path err_file = dir / "stderr.txt";
    // A configuration of its own: no screens kept by whoever runs the tests.
    const std::string cmd = "env XDG_CONFIG_HOME=" + (dir / "config").string() + " " + env + " " +
                            std::string(UMF_REQUESTER_TOOL) + " " + args + " 2>" + err_file.string() + " </dev/null";
    Result r;
    const auto start = std::chrono::steady_clock::now();
    FILE* p = popen(cmd.c_str(), "r");
    if (!p) return r;
    std::array<char, 4096> buf{};
    while (std::size_t n = fread(buf.data(), 1, buf.size(), p)) r.out.append(buf.data(), n);
    const int status = pclose(p);
    r.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    r.code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
    std::ifstream e(err_file);
    r.err.assign(std::istreambuf_iterator<char>(e), {});
    std::istringstream lines(r.out);
    std::vector<std::string> all;
    for (std::string line; std::getline(lines, line);) all.push_back(line);
    EXPECT_EQ(all.size(), 1u) << "stdout: " << r.out << "\nstderr: " << r.err;
    if (!all.empty()) r.line = Json::parse(all.back());  // throws if not JSON
    return r;
}

std::string code_of(const Result& r) {
    if (!r.line.contains("error")) return "";
    return r.line["error"].value("code", "");
}

std::string sha256_hex(const std::string& data) {
    unsigned char md[EVP_MAX_MD_SIZE];
    unsigned int len = 0;
    EVP_Digest(data.data(), data.size(), md, &len, EVP_sha256(), nullptr);
    std::string hex;
    for (unsigned i = 0; i < len; ++i) {
        hex += "0123456789abcdef"[md[i] >> 4];
        hex += "0123456789abcdef"[md[i] & 15];
    }
    return hex;
}

std::vector<std::string> files_in(const fs::path& dir) {
    std::vector<std::string> names;
    for (const auto& e : fs::directory_iterator(dir)) names.push_back(e.path().filename().string());
    std::sort(names.begin(), names.end());
    return names;
}

// Photos and videos of the default field (what the provider's welcome
// carries) are made once: the simulator is the slow part.
class RequesterGrab : public ::testing::Test {
protected:
    static void SetUpTestSuite() {
        shared_dir_ = fs::temp_directory_path() / ("umf_requester_grab_" + std::to_string(::getpid()));
        fs::create_directories(shared_dir_);
        const umf::Field field = default_service_config().screens.field.definition;
        photo_ = new umf::test::Photo(umf::test::photograph_field(field, 0.5, 0, 0, 0, 300));
        const umf::test::Photo blank = umf::test::photograph_field(field, 0, 0, 0, 0, 300);
        ASSERT_TRUE(cv::imwrite(shared("photo.png"), photo_->shot.bgr));
        ASSERT_TRUE(cv::imwrite(shared("blank.png"), blank.shot.bgr));
        const std::pair<const char*, const cv::Mat*> videos[] = {{"clip.avi", &photo_->shot.bgr},
                                                                 {"blank.avi", &blank.shot.bgr}};
        for (const auto& [name, shot] : videos) {
            cv::VideoWriter writer(shared(name), cv::CAP_OPENCV_MJPEG, cv::VideoWriter::fourcc('M', 'J', 'P', 'G'), 10,
                                   shot->size());
            ASSERT_TRUE(writer.isOpened());
            for (int i = 0; i < 15; ++i) writer.write(*shot);
        }
    }
    static void TearDownTestSuite() {
        delete photo_;
        photo_ = nullptr;
        fs::remove_all(shared_dir_);
    }
    void SetUp() override {
        dir_ = shared_dir_ / ::testing::UnitTest::GetInstance()->current_test_info()->name();
        fs::create_directories(dir_);
        identity_ = load_or_create_tls_identity(dir_ / "config");
        token_ = load_or_create_token(dir_ / "config");
    }
    void TearDown() override {
        if (server_) server_->stop();
    }

    void start_server() {
        server_ = make_server(std::make_shared<const Service>(default_service_config(), token_), identity_);
        server_->start();
        ASSERT_NE(server_->port(), 0);
    }
    std::string url(unsigned short port, const std::string& fingerprint, const std::string& token) const {
        return shell_quoted(pairing_url("127.0.0.1", port, token, fingerprint));
    }
    std::string server_url() const { return url(server_->port(), identity_.fingerprint, token_); }
    Result grab(const std::string& url, const std::string& args) const {
        return run("grab --url " + url + " " + args, dir_);
    }
    static std::string shared(const std::string& name) { return (shared_dir_ / name).string(); }
    static cv::Point2d truth() {
        const cv::Point2d centre(photo_->shot.bgr.cols / 2.0, photo_->shot.bgr.rows / 2.0);
        return umf::sim::image_to_field(photo_->shot, photo_->placement, centre);
    }

    static inline fs::path shared_dir_;
    static inline umf::test::Photo* photo_ = nullptr;
    fs::path dir_;
    TlsIdentity identity_;
    std::string token_;
    std::unique_ptr<Server> server_;
};

// ---- against the real server ----------------------------------------------

TEST_F(RequesterGrab, PhotoOfTheFieldIsAimedAndGrabbed) {
    start_server();
    const Result r = grab(server_url(), "--image " + shared("photo.png"));
    // Everything up to the grab worked; the server has nothing to give yet.
    EXPECT_EQ(r.code, 5) << r.err;
    EXPECT_EQ(r.line["ok"], false) << r.line.dump();
    EXPECT_EQ(code_of(r), "nothing_to_take") << r.line.dump();
    EXPECT_NE(r.line["error"].value("message", "").find("nothing to take at that point"), std::string::npos);
    ASSERT_TRUE(r.line.contains("point")) << r.line.dump();
    const cv::Point2d t = truth();
    EXPECT_NEAR(r.line["point"][0].get<double>(), t.x, 0.2) << r.line.dump();
    EXPECT_NEAR(r.line["point"][1].get<double>(), t.y, 0.2) << r.line.dump();
    EXPECT_NE(r.err.find("connected to"), std::string::npos) << r.err;
}

TEST_F(RequesterGrab, VideoGrabsOnceTheAimHoldsSteady) {
    start_server();
    const Result r = grab(server_url(), "--video " + shared("clip.avi") + " --auto --no-window");
    EXPECT_EQ(r.code, 5) << r.err;
    EXPECT_EQ(code_of(r), "nothing_to_take") << r.line.dump() << "\n" << r.err;
    EXPECT_NE(r.err.find("locked on the field"), std::string::npos) << r.err;
}

TEST_F(RequesterGrab, VideoWithoutTheFieldEndsWithoutAGrab) {
    start_server();
    const Result r = grab(server_url(), "--video " + shared("blank.avi") + " --auto --no-window");
    EXPECT_EQ(r.code, 5) << r.err;
    EXPECT_EQ(code_of(r), "not_found_in_view") << r.line.dump();
    EXPECT_NE(r.line["error"].value("message", "").find("never found"), std::string::npos) << r.line.dump();
}

TEST_F(RequesterGrab, PhotoWithoutTheFieldFindsNothing) {
    start_server();
    const Result r = grab(server_url(), "--image " + shared("blank.png"));
    EXPECT_EQ(r.code, 5) << r.err;
    EXPECT_EQ(code_of(r), "not_found_in_view") << r.line.dump();
    EXPECT_NE(r.line["error"].value("message", "").find("the field was not found in"), std::string::npos)
        << r.line.dump();
}

TEST_F(RequesterGrab, WrongTokenIsUnauthorized) {
    start_server();
    const Result r = grab(url(server_->port(), identity_.fingerprint, "not-the-token-0123456789ab"),
                       "--image " + shared("photo.png"));
    EXPECT_EQ(r.code, 4) << r.err;
    EXPECT_EQ(code_of(r), "unauthorized") << r.line.dump();
    EXPECT_NE(r.line["error"].value("message", "").find("pair again"), std::string::npos) << r.line.dump();
}

TEST_F(RequesterGrab, AnotherCertificateIsRefused) {
    start_server();
    const Result r = grab(url(server_->port(), create_tls_identity().fingerprint, token_), "--image " + shared("photo.png"));
    EXPECT_EQ(r.code, 4) << r.err;
    EXPECT_EQ(code_of(r), "certificate") << r.line.dump();
}

TEST_F(RequesterGrab, NoProviderIsAConnectionFailure) {
    // A port that was just free: nothing listens there.
    start_server();
    const unsigned short port = server_->port();
    server_->stop();
    server_.reset();
    const Result r = grab(url(port, identity_.fingerprint, token_), "--image " + shared("photo.png"));
    EXPECT_EQ(r.code, 4) << r.err;
    EXPECT_EQ(code_of(r), "connection") << r.line.dump();
    EXPECT_LT(r.seconds, 10);
}

TEST_F(RequesterGrab, WrongUsageStillPrintsOneJsonLine) {
    const std::string u = url(1, identity_.fingerprint, token_);
    for (const std::string& args : std::vector<std::string>{
             "grab", "grab --url " + u + " --video x.avi --no-window", "grab --url " + u + " --video x.avi",
          "grab --url " + u + " --image a.png --video b.avi", "grab --url 'https://h:1/#t=short&fp=00'",
          "grab --url " + u + " --camera -1 --auto", "grab --url " + u + " --timeout 0 --auto", "grab --url " + u + " x.png"}) {
        const Result r = run(args, dir_);
        EXPECT_EQ(r.code, 2) << args << "\n" << r.err;
        EXPECT_EQ(code_of(r), "usage") << args << "\n" << r.line.dump();
    }
}

TEST_F(RequesterGrab, UnreadableImageIsAnInputErrorBeforeAnyConnection) {
    umf::test::FakeProvider fake(identity_, token_);
    std::ofstream(dir_ / "not-an-image.png") << "text";
    const Result r = grab(url(fake.port(), fake.fingerprint(), token_), "--image " + (dir_ / "not-an-image.png").string());
    EXPECT_EQ(r.code, 3) << r.err;
    EXPECT_EQ(code_of(r), "input") << r.line.dump();
    EXPECT_EQ(fake.requests(), 0);
}

// ---- against the stand-in ---------------------------------------------------

TEST_F(RequesterGrab, AnotherCertificateGetsNoHello) {
    // The stand-in has its own identity; the URL names another one.
    umf::test::FakeProvider fake(create_tls_identity(), token_);
    const Result r = grab(url(fake.port(), identity_.fingerprint, token_), "--image " + shared("photo.png"));
    EXPECT_EQ(r.code, 4) << r.err;
    EXPECT_EQ(code_of(r), "certificate") << r.line.dump();
    EXPECT_NE(r.line["error"].value("message", "").find("nothing was sent"), std::string::npos) << r.line.dump();
    EXPECT_EQ(fake.requests(), 0);
    EXPECT_EQ(fake.hellos(), 0);
}

TEST_F(RequesterGrab, LinkIsPrinted) {
    umf::test::FakeProvider fake(identity_, token_);
    umf::test::FakeContent c;
    c.kind = umf::protocol::ContentKind::url;
    c.title = "umf - GitHub";
    c.url = "https://example.org/umf?x=1";
    fake.set_content(c);
    const Result r = grab(url(fake.port(), fake.fingerprint(), token_), "--image " + shared("photo.png"));
    EXPECT_EQ(r.code, 0) << r.err;
    std::vector<std::string> keys;
    for (const auto& item : r.line.items()) keys.push_back(item.key());
    EXPECT_EQ(keys, (std::vector<std::string>{"ok", "kind", "title", "point", "url", "opened"})) << r.line.dump();
    EXPECT_EQ(r.line["ok"], true);
    EXPECT_EQ(r.line["kind"], "url");
    EXPECT_EQ(r.line["title"], "umf - GitHub");
    EXPECT_EQ(r.line["url"], "https://example.org/umf?x=1");
    EXPECT_EQ(r.line["opened"], false);
    EXPECT_EQ(fake.grabs(), 1);
}

TEST_F(RequesterGrab, VideoAimsWhileLockedAndSeeksWhileNot) {
    umf::test::FakeProvider fake(identity_, token_);
    umf::test::FakeContent c;
    c.kind = umf::protocol::ContentKind::url;
    c.url = "https://example.org/";
    fake.set_content(c);
    const Result locked = grab(url(fake.port(), fake.fingerprint(), token_),
                               "--video " + shared("clip.avi") + " --auto --no-window");
    EXPECT_EQ(locked.code, 0) << locked.err;
    fake.join_connections();
    EXPECT_GE(fake.aims(), 1);
    EXPECT_EQ(fake.seekings(), 0);
    EXPECT_EQ(fake.grabs(), 1);

    const Result searching = grab(url(fake.port(), fake.fingerprint(), token_),
                                  "--video " + shared("blank.avi") + " --auto --no-window");
    EXPECT_EQ(searching.code, 5) << searching.err;
    fake.join_connections();
    EXPECT_GE(fake.seekings(), 1);
    EXPECT_EQ(fake.grabs(), 1);
}

TEST_F(RequesterGrab, FileIsDownloadedAndNeverReplacesOne) {
    umf::test::FakeProvider fake(identity_, token_);
    umf::test::FakeContent c;
    c.body = std::string(200000, 'x') + "end";  // several reads
    c.sha256 = sha256_hex(c.body);
    fake.set_content(c);
    const fs::path out = dir_ / "downloads" / "nested";  // created on demand
    fs::create_directories(out);
    std::ofstream(out / "report.pdf") << "the user's own report";

    const Result first = grab(url(fake.port(), fake.fingerprint(), token_),
                           "--image " + shared("photo.png") + " --out " + out.string());
    ASSERT_EQ(first.code, 0) << first.err;
    std::vector<std::string> keys;
    for (const auto& item : first.line.items()) keys.push_back(item.key());
    EXPECT_EQ(keys, (std::vector<std::string>{"ok", "kind", "title", "point", "saved", "name", "size", "sha256", "mime"}))
        << first.line.dump();
    EXPECT_EQ(first.line["kind"], "file");
    EXPECT_EQ(first.line["name"], "report (1).pdf");
    EXPECT_EQ(first.line["saved"], (out / "report (1).pdf").string());
    EXPECT_EQ(first.line["size"], c.body.size());
    EXPECT_EQ(first.line["sha256"], *c.sha256);
    EXPECT_EQ(read_file(out / "report (1).pdf"), c.body);
    EXPECT_EQ(read_file(out / "report.pdf"), "the user's own report");

    const Result second = grab(url(fake.port(), fake.fingerprint(), token_),
                            "--image " + shared("photo.png") + " --out " + out.string());
    ASSERT_EQ(second.code, 0) << second.err;
    EXPECT_EQ(second.line["name"], "report (2).pdf");
    EXPECT_EQ(files_in(out), (std::vector<std::string>{"report (1).pdf", "report (2).pdf", "report.pdf"}));
    EXPECT_EQ(fake.downloads(), 2);
}

TEST_F(RequesterGrab, MissingOutputDirectoryIsCreated) {
    umf::test::FakeProvider fake(identity_, token_);
    umf::test::FakeContent c;
    c.kind = umf::protocol::ContentKind::snapshot;
    c.name = "screen.png";
    c.body = "";  // an empty file is a file too
    fake.set_content(c);
    const fs::path out = dir_ / "a" / "b";
    const Result r = grab(url(fake.port(), fake.fingerprint(), token_),
                       "--image " + shared("photo.png") + " --out " + out.string());
    ASSERT_EQ(r.code, 0) << r.err;
    EXPECT_EQ(r.line["kind"], "snapshot");
    EXPECT_EQ(r.line["size"], 0);
    EXPECT_EQ(r.line["sha256"], sha256_hex(""));
    EXPECT_EQ(files_in(out), (std::vector<std::string>{"screen.png"}));
}

// A download cut off after half its bytes is asked again for the rest (Range
// from 50000, If-Range with the ETag), says so on stderr, and arrives whole
// and checked.
TEST_F(RequesterGrab, ACutDownloadResumesAndArrivesWhole) {
    umf::test::FakeProvider fake(identity_, token_);
    umf::test::FakeContent c;
    c.body = std::string(60000, 'a') + std::string(40000, 'b');
    c.sha256 = sha256_hex(c.body);
    c.sent_bytes = 50000;
    fake.set_content(c);
    const fs::path out = dir_ / "resumed";
    fs::create_directories(out);
    const Result r = grab(url(fake.port(), fake.fingerprint(), token_),
                          "--image " + shared("photo.png") + " --out " + out.string());
    ASSERT_EQ(r.code, 0) << r.err;
    EXPECT_EQ(read_file(out / "report.pdf"), c.body);
    EXPECT_EQ(r.line["sha256"], *c.sha256);
    EXPECT_EQ(fake.downloads(), 2) << "one request for the whole, one for the rest";
    EXPECT_NE(r.err.find("the connection was lost at 0.1 MB of 0.1 MB"), std::string::npos) << r.err;
    EXPECT_NE(r.err.find("resuming in 250 ms"), std::string::npos) << r.err;
    EXPECT_EQ(files_in(out), (std::vector<std::string>{"report.pdf"})) << "no partial file is left";
}

// The download's own connection is pinned like the session's: a provider
// that shows another certificate there gets no request and keeps nothing.
TEST_F(RequesterGrab, ADownloadFromAnotherCertificateIsRefused) {
    umf::test::FakeProvider fake(identity_, token_);
    umf::test::FakeContent c;
    c.body = std::string(100000, 'z');
    c.download_identity = create_tls_identity();
    fake.set_content(c);
    const fs::path out = dir_ / "other-certificate";
    fs::create_directories(out);
    const Result r = grab(url(fake.port(), fake.fingerprint(), token_),
                          "--image " + shared("photo.png") + " --out " + out.string());
    EXPECT_EQ(r.code, 4) << r.err;
    EXPECT_EQ(code_of(r), "certificate") << r.line.dump();
    fake.join_connections();
    EXPECT_EQ(fake.downloads(), 0) << "the download's request was never sent";
    EXPECT_TRUE(files_in(out).empty());
}

TEST_F(RequesterGrab, BadTransfersLeaveNothingBehind) {
    umf::test::FakeProvider fake(identity_, token_);
    struct Case {
        const char* what;
        umf::test::FakeContent content;
        const char* code;
        int exit;
        const char* says = "";  // in the line's message
    };
    umf::test::FakeContent wrong_sha, gone_at_resume, changed_at_resume, wrong_size, expired, failed;
    wrong_sha.sha256 = sha256_hex("something else");
    gone_at_resume.body = changed_at_resume.body = std::string(100000, 'y');
    gone_at_resume.sent_bytes = changed_at_resume.sent_bytes = 50000;
    gone_at_resume.resume_status = 404;
    changed_at_resume.resume_status = 409;
    wrong_size.size = static_cast<std::int64_t>(wrong_size.body.size()) + 1;
    expired.status = 404;
    failed.status = 500;
    const Case cases[] = {{"wrong sha256", wrong_sha, "download", 4},
                          {"cut off, the link gone when resuming", gone_at_resume, "not_found", 5,
                           "after 50000 of 100000 bytes and its link was gone when the rest was asked for"},
                          // The provider's reason, from its error body.
                          {"cut off, the file changed when resuming", changed_at_resume, "internal", 4,
                           "the file changed since it was offered"},
                          {"size differs from Content-Length", wrong_size, "download", 4},
                          {"expired link", expired, "not_found", 5, "unknown, finished or expired download link"},
                          {"server error", failed, "internal", 4, "the provider failed"}};
    for (const auto& c : cases) {
        fake.set_content(c.content);
        const fs::path out = dir_ / "out";
        fs::create_directories(out);
        const Result r = grab(url(fake.port(), fake.fingerprint(), token_),
                           "--image " + shared("photo.png") + " --out " + out.string());
        EXPECT_EQ(r.code, c.exit) << c.what << "\n" << r.err;
        EXPECT_EQ(code_of(r), c.code) << c.what << "\n" << r.line.dump();
        EXPECT_NE(r.line.dump().find(c.says), std::string::npos) << c.what << "\n" << r.line.dump();
        EXPECT_TRUE(files_in(out).empty()) << c.what;
    }
}

}  // namespace

#endif
