// What the person at the screen reads of puts, and what a trusted device's
// puts do: each step of a put (asked, accepted, refused, timed out,
// withdrawn, stored, opened, failed) reaches the activity listener and the
// console as one terminal-safe line, driven through the service as a session
// would drive it; a device accepted "always" keeps the Open or Save chosen
// with it, in a trusted-devices.json an older provider still reads.
#ifdef UMF_PROVIDER_TESTS

#include <gtest/gtest.h>

#include <algorithm>
#include <condition_variable>
#include <fstream>
#include <mutex>
#include <nlohmann/json.hpp>
#include <sstream>

#include "provider/content/file_facts.hpp"
#include "provider/put/put_desk.hpp"
#include "provider/put/trusted_devices.hpp"
#include "provider/put/upload_sink.hpp"
#include "provider/service/console_activity.hpp"
#include "provider/service/service.hpp"
#include "shared/protocol/messages.hpp"
#include "tests/provider/put_test_support.hpp"
#include "tests/support/temp_dir.hpp"

namespace {

namespace fs = std::filesystem;
namespace p = umf::protocol;
using namespace umf::provider;
using umf::test::FakeXdgOpen;
using umf::test::ScriptedDecider;
using umf::test::TempDir;
using umf::test::file_put;
using umf::test::url_put;

constexpr const char* kActivityToken = "put-activity-token-0123456789";

// Every put step heard, in order, from whichever thread.
class ActivityRecorder : public ActivityListener {
public:
    void seeking(std::uint64_t) override {}
    void aimed(const AimActivity&) override {}
    void left(std::uint64_t) override {}
    void put(const PutActivity& a) override {
        std::lock_guard lock(mutex_);
        steps_.push_back(a);
        changed_.notify_all();
    }
    // The steps so far, waiting up to 5 s for at least n.
    std::vector<PutActivity> steps(std::size_t n = 0) {
        std::unique_lock lock(mutex_);
        changed_.wait_for(lock, std::chrono::seconds(5), [&] { return steps_.size() >= n; });
        return steps_;
    }
    std::vector<PutStage> stages(std::size_t n = 0) {
        std::vector<PutStage> out;
        for (const auto& s : steps(n)) out.push_back(s.stage);
        return out;
    }

private:
    std::mutex mutex_;
    std::condition_variable changed_;
    std::vector<PutActivity> steps_;
};

class PutActivityTest : public ::testing::Test {
protected:
    TempDir dir;
    fs::path folder = dir.path / "Downloads";
    fs::path trusted_file = dir.path / "cfg" / kTrustedDevicesFile;
    FakeXdgOpen xdg{dir.path / "bin"};
    std::shared_ptr<ScriptedDecider> decider = std::make_shared<ScriptedDecider>();
    std::shared_ptr<ActivityRecorder> recorder = std::make_shared<ActivityRecorder>();
    std::ostringstream console_text;
    std::unique_ptr<Service> service;
    std::mutex mutex;
    std::condition_variable pushed_cv;
    std::vector<std::string> pushed;

    void make(std::chrono::milliseconds timeout = std::chrono::seconds(30), std::int64_t max_bytes = 1 << 20) {
        ServiceConfig config = default_service_config();
        config.put_decider = decider;
        config.puts.folder = folder;
        config.puts.answer_timeout = timeout;
        config.puts.max_bytes = max_bytes;
        config.puts.trusted_devices = trusted_file;
        // The console in front, as `serve` has it, the recorder behind.
        service = std::make_unique<Service>(std::move(config), kActivityToken, std::vector<std::shared_ptr<const Resolver>>{},
                                            nullptr, std::make_shared<ConsoleActivity>(console_text, recorder));
    }
    void SetUp() override { make(); }

    void welcome(SessionState& s, const std::optional<std::string>& device) {
        s.outbox = [this](std::uint64_t, std::string message) {
            std::lock_guard lock(mutex);
            pushed.push_back(std::move(message));
            pushed_cv.notify_all();
        };
        const auto out = service->handle_text(s, p::encode(p::Hello{p::RequestId{std::int64_t{1}}, kActivityToken,
                                                                     "Pixel 7", device}));
        ASSERT_EQ(out.replies.size(), 1u);
        ASSERT_TRUE(std::holds_alternative<p::Welcome>(out.replies[0]));
    }
    p::Message put(SessionState& s, const p::Put& m) {
        auto out = service->handle_text(s, p::encode(m));
        EXPECT_EQ(out.replies.size(), 1u);
        return out.replies.at(0);
    }
    std::optional<p::Message> push(std::size_t n) {
        std::unique_lock lock(mutex);
        if (!pushed_cv.wait_for(lock, std::chrono::seconds(5), [&] { return pushed.size() > n; })) return std::nullopt;
        return std::get<p::Message>(p::parse_message(pushed[n], p::kRequesterLimits));
    }
    // The upload as the session does it: the link's entry, the bytes, done.
    std::string upload(const std::string& link, const std::string& bytes) {
        auto checkout = service->puts().begin_upload(link);
        EXPECT_TRUE(checkout);
        if (!checkout) return {};
        UploadSink sink(checkout->entry.folder, checkout->entry.size, checkout->entry.sha256);
        sink.write(bytes.data(), bytes.size());
        const std::string stored = sink.store(checkout->entry.name);
        service->puts().end_upload(*checkout, UploadEnd::stored);
        service->puts().upload_done(checkout->entry, stored);
        return stored;
    }
    std::vector<std::string> console_lines() const {
        std::vector<std::string> lines;
        std::istringstream in(console_text.str());
        for (std::string line; std::getline(in, line);)
            if (line.rfind("requester", 0) == 0 && line.find(" connected: ") == std::string::npos)
                lines.push_back(line);
        return lines;
    }
};

std::string link_of(const p::Message& m) {
    const auto* s = std::get_if<p::PutStatus>(&m);
    EXPECT_TRUE(s && s->upload) << p::type_name(m);
    return s && s->upload ? *s->upload : std::string();
}

TEST_F(PutActivityTest, AFilePutIsToldFromAskingToSaved) {
    SessionState state;
    welcome(state, "Pixel 7");
    put(state, file_put("hello", "a"));
    decider->answer(decider->offers(1).at(0).id, {PutAnswer::save, false});
    const auto answer = push(0);
    ASSERT_TRUE(answer);
    const std::string stored = upload(link_of(*answer), "hello");
    // A second one of the same name is saved beside it, not over it.
    put(state, file_put("world", "b"));
    decider->answer(decider->offers(2).at(1).id, {PutAnswer::save, false});
    const auto second = push(2);  // after the first one's "done"
    ASSERT_TRUE(second);
    EXPECT_EQ(upload(link_of(*second), "world"), "report (1).pdf");

    EXPECT_EQ(recorder->stages(6), (std::vector<PutStage>{PutStage::asking, PutStage::accepted, PutStage::stored,
                                                           PutStage::asking, PutStage::accepted, PutStage::stored}));
    const auto steps = recorder->steps();
    EXPECT_EQ(steps[0].session, state.id);
    EXPECT_EQ(steps[0].name, "report.pdf");
    EXPECT_EQ(steps[0].size, 5);
    EXPECT_EQ(steps[0].device, "Pixel 7");
    EXPECT_EQ(steps[1].answer, "save");
    EXPECT_EQ(steps[2].path, (folder / stored).string());
    const std::string n = std::to_string(state.id);
    EXPECT_EQ(console_lines(),
              (std::vector<std::string>{
                  "requester " + n + " puts file \"report.pdf\" (5 bytes) from \"Pixel 7\": asking the screen",
                  "requester " + n + "'s put \"report.pdf\": accepted (save)",
                  "requester " + n + " put report.pdf (5 bytes) \u2192 saved as " + (folder / "report.pdf").string(),
                  "requester " + n + " puts file \"report.pdf\" (5 bytes) from \"Pixel 7\": asking the screen",
                  "requester " + n + "'s put \"report.pdf\": accepted (save)",
                  "requester " + n + " put report.pdf (5 bytes) \u2192 saved as " +
                      (folder / "report (1).pdf").string(),
              }));
}

TEST_F(PutActivityTest, OpenedUrlsAndFilesSaySo) {
    SessionState state;
    welcome(state, std::nullopt);
    put(state, url_put("u"));
    decider->answer(decider->offers(1).at(0).id, {PutAnswer::open, false});
    ASSERT_TRUE(push(0));
    put(state, file_put("slides", "f", "deck.pdf"));
    decider->answer(decider->offers(2).at(1).id, {PutAnswer::open, false});
    const auto answer = push(1);
    ASSERT_TRUE(answer);
    upload(link_of(*answer), "slides");
    EXPECT_EQ(xdg.opened(2), (std::vector<std::string>{"https://example.org/talk", (folder / "deck.pdf").string()}));
    EXPECT_EQ(recorder->stages(6), (std::vector<PutStage>{PutStage::asking, PutStage::accepted, PutStage::opened,
                                                           PutStage::asking, PutStage::accepted, PutStage::opened}));
    const auto lines = console_lines();
    ASSERT_EQ(lines.size(), 6u);
    const std::string n = std::to_string(state.id);
    EXPECT_EQ(lines[0], "requester " + n + " puts url \"Talk page\" <https://example.org/talk> from \"Pixel 7\": asking the screen");
    EXPECT_EQ(lines[2], "requester " + n + " put url <https://example.org/talk> \u2192 opened");
    EXPECT_EQ(lines[5], "requester " + n + " put deck.pdf (6 bytes) \u2192 saved as " + (folder / "deck.pdf").string() +
                            " and opened");
}

TEST_F(PutActivityTest, RefusalsTimeoutsDeparturesAndFailuresAreTold) {
    // Long enough for the departure below to come before the deadline.
    make(std::chrono::milliseconds(1000), 100);
    SessionState state;
    welcome(state, std::nullopt);
    // Too large: refused before anyone is asked.
    put(state, file_put(std::string(101, 'x'), "big"));
    // Dismissed at the screen.
    put(state, url_put("no"));
    decider->answer(decider->offers(1).at(0).id, {PutAnswer::dismiss, false});
    ASSERT_TRUE(push(0));
    // Nobody answers.
    put(state, url_put("late"));
    ASSERT_TRUE(push(1));
    // Accepted, then the upload breaks off.
    put(state, file_put("abc", "cut", "notes.txt"));
    decider->answer(decider->offers(3).at(2).id, {PutAnswer::save, false});
    const auto answer = push(2);
    ASSERT_TRUE(answer);
    const auto checkout = service->puts().begin_upload(link_of(*answer));
    ASSERT_TRUE(checkout);
    service->puts().end_upload(*checkout, UploadEnd::failed);
    service->puts().upload_failed(checkout->entry, p::ErrorCode::interrupted, "the upload broke off after 1 of 3 bytes");
    // Asked, then the requester leaves.
    put(state, url_put("gone"));
    decider->offers(4);
    service->session_ended(state);

    EXPECT_EQ(recorder->stages(10),
              (std::vector<PutStage>{PutStage::refused, PutStage::asking, PutStage::refused, PutStage::asking,
                                     PutStage::timed_out, PutStage::asking, PutStage::accepted, PutStage::failed,
                                     PutStage::asking, PutStage::withdrawn}));
    const auto lines = console_lines();
    const std::string n = std::to_string(state.id);
    ASSERT_GE(lines.size(), 10u);
    EXPECT_EQ(lines[0], "requester " + n + " puts file \"report.pdf\" (101 bytes) from \"Pixel 7\": refused (report.pdf is 101 bytes, "
                        "more than the limit of 100)");
    EXPECT_EQ(lines[2], "requester " + n + "'s put \"Talk page\": refused (declined at the screen)");
    EXPECT_EQ(lines[4], "requester " + n + "'s put \"Talk page\": timed out (no answer within 1 s)");
    EXPECT_EQ(lines[7], "requester " + n + "'s put \"notes.txt\": failed (interrupted: the upload broke off after 1 of 3 bytes)");
    EXPECT_EQ(lines[9], "requester " + n + "'s put \"Talk page\": withdrawn, the requester left");
}

TEST_F(PutActivityTest, ThePhonesTextCannotDriveTheTerminal) {
    SessionState state;
    welcome(state, "Pixel 7");
    // A file name that turns "fdp.exe" around to read "exe.pdf", and a URL
    // title that would clear the screen, retitle the terminal and start a
    // line of its own.
    put(state, file_put("x", "evil", "invoice\xe2\x80\xae" "fdp.exe"));
    p::Put url = url_put("title");
    url.title = "Talk\x1b]0;owned\x07\x1b[2J\nrequester 1 put fake.pdf";
    put(state, url);
    decider->offers(2);
    const std::string text = console_text.str();
    EXPECT_EQ(text.find('\x1b'), std::string::npos);
    EXPECT_EQ(text.find('\x07'), std::string::npos);
    EXPECT_EQ(text.find("\xe2\x80\xae"), std::string::npos) << "no right-to-left override";
    // The welcome's line and one for each put, no more.
    EXPECT_EQ(std::count(text.begin(), text.end(), '\n'), 3) << text;
    EXPECT_NE(text.find("\"invoice?fdp.exe\""), std::string::npos) << text;
}

TEST_F(PutActivityTest, OpenWithAlwaysOpensThatDevicesFilesFromThenOn) {
    SessionState state;
    welcome(state, "Pixel 7");
    put(state, file_put("one", "1", "a.pdf"));
    decider->answer(decider->offers(1).at(0).id, {PutAnswer::open, true});
    const auto first = push(0);
    ASSERT_TRUE(first);
    upload(link_of(*first), "one");
    // Not asked again, and opened again.
    const auto second = put(state, file_put("two", "2", "b.pdf"));
    EXPECT_EQ(decider->offers(0).size(), 1u);
    const auto checkout = service->puts().begin_upload(link_of(second));
    ASSERT_TRUE(checkout);
    EXPECT_TRUE(checkout->entry.open);
    const auto steps = recorder->steps();
    ASSERT_FALSE(steps.empty());
    EXPECT_EQ(steps.back().stage, PutStage::accepted);
    EXPECT_TRUE(steps.back().trusted);
    EXPECT_EQ(steps.back().answer, "open");
    EXPECT_NE(console_lines().back().find("accepted (open, a device always accepted)"), std::string::npos)
        << console_lines().back();
    // Kept for the next run.
    const auto doc = nlohmann::json::parse(umf::test::file_text(trusted_file));
    EXPECT_EQ(doc["devices"], nlohmann::json::array({"Pixel 7"}));
    EXPECT_EQ(doc["open_files"], nlohmann::json::array({"Pixel 7"}));
    EXPECT_EQ(TrustedDevices(trusted_file).files_answer("Pixel 7"), PutAnswer::open);
}

TEST_F(PutActivityTest, SaveWithAlwaysSavesAndAUrlsAlwaysKeepsTheFilesChoice) {
    SessionState saver, opener;
    welcome(saver, "tablet");
    welcome(opener, "Pixel 7");
    put(saver, file_put("one", "1"));
    decider->answer(decider->offers(1).at(0).id, {PutAnswer::save, true});
    ASSERT_TRUE(push(0));
    const auto saved = put(saver, file_put("two", "2"));
    const auto saved_lease = service->puts().begin_upload(link_of(saved));
    ASSERT_TRUE(saved_lease);
    EXPECT_FALSE(saved_lease->entry.open);

    // Pixel 7 opens its files; a URL accepted with "always" later keeps that.
    service->puts().trusted().add("Pixel 7", PutAnswer::open);
    service->puts().trusted().add("Pixel 7");
    EXPECT_EQ(service->puts().trusted().files_answer("Pixel 7"), PutAnswer::open);
    const auto url = put(opener, url_put("u"));
    EXPECT_EQ(std::get<p::PutStatus>(url).outcome, p::PutOutcome::opened) << "a URL is opened, never saved";
    // A new device whose first "always" was for a URL saves its files.
    SessionState fresh;
    welcome(fresh, "laptop");
    put(fresh, url_put("v"));
    decider->answer(decider->offers(2).at(1).id, {PutAnswer::open, true});
    ASSERT_TRUE(push(1));
    EXPECT_EQ(service->puts().trusted().files_answer("laptop"), PutAnswer::save);
}

TEST_F(PutActivityTest, AStandingAnswerIsToldWithoutAsking) {
    // As `--puts always`: answered within ask, so nobody was asked.
    decider = std::make_shared<ScriptedDecider>(ScriptedDecider::Mode::at_once);
    make();
    SessionState state;
    welcome(state, std::nullopt);
    put(state, file_put("hi", "a"));
    const std::string n = std::to_string(state.id);
    EXPECT_EQ(console_lines(),
              std::vector<std::string>{"requester " + n + " puts file \"report.pdf\" (2 bytes) from \"Pixel 7\": accepted (save)"});
    EXPECT_FALSE(recorder->steps().at(0).asked);
}

TEST(PutTrustedDevices, AListFromBeforeTheChoiceMeansSave) {
    TempDir dir;
    const fs::path file = dir.path / kTrustedDevicesFile;
    std::ofstream(file) << R"({"format": "umf-trusted-devices/1", "devices": ["Pixel 7", "tablet"]})";
    TrustedDevices devices(file);
    EXPECT_EQ(devices.files_answer("Pixel 7"), PutAnswer::save);
    EXPECT_EQ(devices.files_answer("tablet"), PutAnswer::save);
    EXPECT_EQ(devices.files_answer("other"), std::nullopt);
    EXPECT_EQ(devices.files_answer(""), std::nullopt);
    // Changing one choice keeps "devices" as an older provider reads it.
    EXPECT_TRUE(devices.add("tablet", PutAnswer::open));
    const auto doc = nlohmann::json::parse(umf::test::file_text(file));
    EXPECT_EQ(doc["format"], "umf-trusted-devices/1");
    EXPECT_EQ(doc["devices"], nlohmann::json::array({"Pixel 7", "tablet"}));
    EXPECT_EQ(doc["open_files"], nlohmann::json::array({"tablet"}));
    // Back to save, and gone: the choice goes with the device.
    EXPECT_TRUE(devices.add("tablet", PutAnswer::save));
    EXPECT_FALSE(nlohmann::json::parse(umf::test::file_text(file)).contains("open_files"));
    EXPECT_TRUE(devices.add("tablet", PutAnswer::open));
    EXPECT_TRUE(devices.remove("tablet"));
    EXPECT_TRUE(devices.add("tablet"));
    EXPECT_EQ(devices.files_answer("tablet"), PutAnswer::save);
    EXPECT_FALSE(devices.add("phone", PutAnswer::dismiss)) << "dismiss is no standing choice";
    EXPECT_FALSE(devices.contains("phone"));
}

TEST(PutTrustedDevices, OpenFilesNamingAnUnknownDeviceTrustsNobody) {
    TempDir dir;
    const fs::path file = dir.path / kTrustedDevicesFile;
    std::ofstream(file) << R"({"format": "umf-trusted-devices/1", "devices": ["a"], "open_files": ["b", 3, "a"]})";
    TrustedDevices devices(file);
    EXPECT_EQ(devices.files_answer("a"), PutAnswer::open);
    EXPECT_EQ(devices.files_answer("b"), std::nullopt);
    EXPECT_EQ(devices.size(), 1u);
}

}  // namespace

#endif
