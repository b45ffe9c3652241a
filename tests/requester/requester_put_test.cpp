// umf-requester put through its program against the real provider server
// with puts (the screen's answers scripted in the test): a video aimed until
// steady, the device name kept between runs and trusted by the screen, and
// every wrong usage or unreadable file answered with its JSON line before
// any connection. The two-provider story is in put_end_to_end_test.cpp.
#if defined(UMF_PROVIDER_TESTS) && defined(UMF_REQUESTER_TOOL)

#include <gtest/gtest.h>
#include <sys/wait.h>
#include <unistd.h>

#include <array>
#include <atomic>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <memory>
#include <mutex>
#include <nlohmann/json.hpp>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/videoio.hpp>
#include <sstream>
#include <string>
#include <vector>

#include "provider/put/put_decision.hpp"
#include "provider/service/pairing.hpp"
#include "provider/service/service.hpp"
#include "provider/service/service_server.hpp"
#include "provider/trust/tls_identity_store.hpp"
#include "tests/detect/photo.hpp"
#include "tests/requester/fake_provider.hpp"
#include "tests/support/files.hpp"
#include "tests/support/process.hpp"
#include "tests/support/temp_dir.hpp"

namespace {

namespace fs = std::filesystem;
using umf::test::read_file;
using umf::test::shell_quoted;
using PutJson = nlohmann::json;
using namespace umf::provider;

struct Outcome {
    int code = -1;
    PutJson line;
    std::string err;
};

// Accepts every put (saving files) and says "always from this device";
// counts how often it was asked.
class TrustingDecider : public PutDecider {
public:
    void ask(const PutOffer& offer, std::function<void(PutReply)> answer) override {
        ++asked;
        {
            std::lock_guard lock(mutex);
            client = offer.client;
        }
        answer(PutReply{PutAnswer::save, true});
    }
    void withdraw(std::uint64_t) override {}
    std::atomic<int> asked{0};
    std::mutex mutex;
    std::string client;  // the last offer's
};

class RequesterPut : public ::testing::Test {
protected:
    static void SetUpTestSuite() {
        shared_ = new umf::test::TempDir("umf-requester-put");
        const umf::Field field = default_service_config().screens.field.definition;
        const umf::test::Photo photo = umf::test::photograph_field(field, 0.5, 0, 0, 0, 300);
        cv::VideoWriter writer((shared_->path / "clip.avi").string(), cv::CAP_OPENCV_MJPEG,
                               cv::VideoWriter::fourcc('M', 'J', 'P', 'G'), 10, photo.shot.bgr.size());
        ASSERT_TRUE(writer.isOpened());
        for (int i = 0; i < 15; ++i) writer.write(photo.shot.bgr);
        ASSERT_TRUE(cv::imwrite((shared_->path / "photo.png").string(), photo.shot.bgr));
    }
    static void TearDownTestSuite() {
        delete shared_;
        shared_ = nullptr;
    }
    void SetUp() override {
        identity_ = load_or_create_tls_identity(dir_.path / "config");
        token_ = load_or_create_token(dir_.path / "config");
    }
    void TearDown() override {
        if (server_) server_->stop();
    }
    void start_server() {
        ServiceConfig config = default_service_config();
        config.put_decider = decider_;
        config.puts.folder = dir_.path / "screen";
        fs::create_directories(config.puts.folder);
        config.puts.trusted_devices = dir_.path / "config" / "trusted-devices.json";
        server_ = make_server(std::make_shared<const Service>(std::move(config), token_), identity_);
        server_->start();
        ASSERT_NE(server_->port(), 0);
    }
    std::string url(unsigned short port, const std::string& fingerprint) const {
        return shell_quoted(pairing_url("127.0.0.1", port, token_, fingerprint));
    }
    std::string server_url() const { return url(server_->port(), identity_.fingerprint); }

    // Runs umf-requester with `args`; stdout must be exactly one JSON line.
    Outcome run(const std::string& args) const {
        const fs::path err_file = dir_.path / "stderr.txt";
        const std::string cmd = "env DISPLAY= WAYLAND_DISPLAY= XDG_CONFIG_HOME=" + (dir_.path / "phone").string() +
                                " " + UMF_REQUESTER_TOOL + " " + args + " 2>" + err_file.string() + " </dev/null";
        Outcome o;
        FILE* p = popen(cmd.c_str(), "r");
        if (!p) return o;
        std::string out;
        std::array<char, 4096> buf{};
        while (std::size_t n = fread(buf.data(), 1, buf.size(), p)) out.append(buf.data(), n);
        const int status = pclose(p);
        o.code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
        o.err = read_file(err_file);
        EXPECT_EQ(std::count(out.begin(), out.end(), '\n'), 1) << "stdout: " << out << "\nstderr: " << o.err;
        o.line = PutJson::parse(out.substr(0, out.find('\n')), nullptr, false);
        return o;
    }
    static std::string code_of(const Outcome& o) {
        return o.line.contains("error") ? o.line["error"].value("code", "") : "";
    }
    static std::string shared(const std::string& name) { return (shared_->path / name).string(); }

    static inline umf::test::TempDir* shared_ = nullptr;
    umf::test::TempDir dir_{"umf-requester-put-case"};
    TlsIdentity identity_;
    std::string token_;
    std::shared_ptr<TrustingDecider> decider_ = std::make_shared<TrustingDecider>();
    std::unique_ptr<Server> server_;
};

TEST_F(RequesterPut, AVideoPutsOnceTheAimHoldsSteadyAndTheScreenTrustsTheDeviceAfter) {
    start_server();
    std::ofstream(dir_.path / "notes.md") << "# Notes\nfrom the phone\n";
    const Outcome first = run("put " + (dir_.path / "notes.md").string() + " --url " + server_url() + " --video " +
                              shared("clip.avi") + " --no-window --auto");
    ASSERT_EQ(first.code, 0) << first.err;
    EXPECT_EQ(first.line.value("outcome", ""), "saved") << first.line.dump();
    EXPECT_EQ(first.line.value("name", ""), "notes.md");
    EXPECT_EQ(first.line["point"].size(), 2u);
    EXPECT_EQ(read_file(dir_.path / "screen" / "notes.md"), "# Notes\nfrom the phone\n");
    EXPECT_EQ(decider_->asked, 1);
    // The prompt names the program and the computer it runs on.
    char host[256] = {};
    ::gethostname(host, sizeof host - 1);
    {
        std::lock_guard lock(decider_->mutex);
        const std::string& c = decider_->client;
        EXPECT_EQ(c.rfind("umf-requester/", 0), 0u) << c;
        const std::string on = std::string(" on ") + host;
        EXPECT_TRUE(c.size() > on.size() && c.compare(c.size() - on.size(), on.size(), on) == 0) << c;
    }

    // The device's name was kept on the phone and remembered by the screen.
    const fs::path device_file = dir_.path / "phone" / "umf" / "requester-device";
    std::string device;
    std::getline(std::ifstream(device_file), device);
    EXPECT_EQ(device.rfind("umf-requester-", 0), 0u) << device;
    EXPECT_EQ(device.size(), std::string("umf-requester-").size() + 32);
    EXPECT_NE(read_file(dir_.path / "config" / "trusted-devices.json").find(device), std::string::npos);

    // The next put from this device is not asked about, and keeps the first file.
    const Outcome second = run("put " + (dir_.path / "notes.md").string() + " --url " + server_url() + " --image " +
                               shared("photo.png"));
    ASSERT_EQ(second.code, 0) << second.err;
    EXPECT_EQ(second.line.value("name", ""), "notes (1).md") << second.line.dump();
    EXPECT_EQ(decider_->asked, 1);
    std::string again;
    std::getline(std::ifstream(device_file), again);
    EXPECT_EQ(again, device);
}

TEST_F(RequesterPut, WrongUsageStillPrintsOneJsonLine) {
    const std::string u = url(1, identity_.fingerprint);
    std::ofstream(dir_.path / "a.txt") << "a";
    const std::string a = (dir_.path / "a.txt").string();
    for (const std::string& args : std::vector<std::string>{
             "put --url " + u + " --image x.png",                             // nothing to put
             "put " + a + " " + a + " --url " + u + " --image x.png",         // two things
             "put " + a + " --image x.png",                                   // no --url
             "put 'https://exa mple.org/' --url " + u + " --image x.png",     // not a link
             "put " + a + " --url " + u + " --title " + std::string(600, 't') + " --image x.png",
             "put " + a + " --url " + u + " --video x.avi --no-window",       // no --auto
             "put " + a + " --url " + u + " --out d --image x.png"}) {        // grab's option
        const Outcome o = run(args);
        EXPECT_EQ(o.code, 2) << args << "\n" << o.err;
        EXPECT_EQ(code_of(o), "usage") << args << "\n" << o.line.dump();
    }
}

TEST_F(RequesterPut, AnUnreadableFileIsAnInputErrorBeforeAnyConnection) {
    umf::test::FakeProvider fake(identity_, token_);
    const std::string u = url(fake.port(), fake.fingerprint());
    for (const std::string& what : {(dir_.path / "missing.pdf").string(), dir_.path.string()}) {
        const Outcome o = run("put " + shell_quoted(what) + " --url " + u + " --image " + shared("photo.png"));
        EXPECT_EQ(o.code, 3) << o.err;
        EXPECT_EQ(code_of(o), "input") << o.line.dump();
    }
    EXPECT_EQ(fake.requests(), 0);
}

}  // namespace

#endif
