// Answers to puts without the desktop prompt: the control socket's requests
// and the `umf-provider puts` command over a real socket in a temporary
// XDG_RUNTIME_DIR, the first answer of several deciders, the fixed answer;
// also the default put folder and the texts the prompt and the command show.
#if defined(UMF_PROVIDER_TESTS)

#include <gtest/gtest.h>

#include <stdlib.h>

#include <atomic>
#include <fstream>
#include <mutex>
#include <optional>
#include <sstream>
#include <thread>
#include <vector>

#include "provider/commands/pair_command.hpp"
#include "provider/content/shared_items.hpp"
#include "provider/put/put_deciders.hpp"
#include "provider/put/put_folder.hpp"
#include "provider/put/put_text.hpp"
#include "provider/service/control_socket.hpp"
#include "shared/cli/args.hpp"
#include "tests/support/scoped_env.hpp"
#include "tests/support/temp_dir.hpp"

namespace {

using namespace umf::provider;
using umf::test::TempDir;
namespace fs = std::filesystem;

PutOffer control_file_offer(std::uint64_t id) {
    PutOffer o;
    o.id = id;
    o.client = "Pixel 7";
    o.device = "d-4f2a";
    o.kind = umf::protocol::ContentKind::file;
    o.name = "report.pdf";
    o.mime = "application/pdf";
    o.size = 2411724;
    return o;
}

PutOffer control_url_offer(std::uint64_t id) {
    PutOffer o;
    o.id = id;
    o.client = "umf-web/0.1 (Android; Chrome 120)";
    o.kind = umf::protocol::ContentKind::url;
    o.url = "https://example.org/talk";
    o.title = "Talk page";
    return o;
}

struct ControlAnswers {
    std::mutex mutex;
    std::vector<PutReply> replies;
    std::function<void(PutReply)> callback() {
        return [this](PutReply r) {
            std::lock_guard lock(mutex);
            replies.push_back(r);
        };
    }
    std::size_t count() {
        std::lock_guard lock(mutex);
        return replies.size();
    }
};

// An environment variable set for one test, restored after it.
using umf::test::ScopedEnv;

constexpr unsigned short kPort = 47999;

umf::cli::Args puts_args(std::vector<std::pair<std::string, std::string>> named = {},
                         std::vector<std::string> flags = {}) {
    umf::cli::Args a;
    a.named["port"] = std::to_string(kPort);
    for (auto& [k, v] : named) a.named[k] = v;
    a.flags = std::move(flags);
    return a;
}

struct Outcome {
    int code;
    std::string out, err;
};

Outcome run(const umf::cli::Args& a) {
    std::ostringstream out, err;
    const int code = run_puts(a, out, err);
    return {code, out.str(), err.str()};
}

TEST(PutControl, ThePutsCommandListsAcceptsAndDismissesOverTheSocket) {
    TempDir runtime;
    ScopedEnv env("XDG_RUNTIME_DIR", runtime.path.string());
    auto puts = std::make_shared<ControlPutDecider>();
    ControlSocket socket(umf::control_socket_path(kPort), std::make_shared<SharedItems>(), puts);
    EXPECT_EQ(socket.path(), runtime.path / "umf" / ("provider-" + std::to_string(kPort) + ".sock"));

    Outcome none = run(puts_args());
    EXPECT_EQ(none.code, 0) << none.err;
    EXPECT_EQ(none.out, "no puts are waiting for an answer\n");

    ControlAnswers a7, a8, a9;
    puts->ask(control_file_offer(7), a7.callback());
    puts->ask(control_url_offer(8), a8.callback());
    puts->ask(control_file_offer(9), a9.callback());
    const Outcome list = run(puts_args());
    ASSERT_EQ(list.code, 0) << list.err;
    std::istringstream lines(list.out);
    std::string header, row7, row8;
    std::getline(lines, header);
    std::getline(lines, row7);
    std::getline(lines, row8);
    EXPECT_EQ(header.rfind("ID  KIND  WHAT", 0), 0u) << header;
    EXPECT_EQ(row7.rfind("7   file  report.pdf", 0), 0u) << row7;
    for (const char* part : {"2.3 MB", "Pixel 7", " s"}) EXPECT_NE(row7.find(part), std::string::npos) << part;
    EXPECT_NE(row8.find("Talk page <https://example.org/talk>"), std::string::npos) << row8;
    EXPECT_NE(row8.find("Chrome 120"), std::string::npos) << row8;
    // --json for scripts: the socket's answer.
    const Outcome json = run(puts_args({}, {"json"}));
    EXPECT_NE(json.out.find(R"("id":7)"), std::string::npos);
    EXPECT_NE(json.out.find(R"("size":2411724)"), std::string::npos);
    EXPECT_NE(json.out.find(R"("url":"https://example.org/talk")"), std::string::npos);

    // --accept ID: save.
    const Outcome accepted = run(puts_args({{"accept", "7"}}));
    EXPECT_EQ(accepted.code, 0) << accepted.err;
    EXPECT_EQ(accepted.out, "put 7 (report.pdf): accepted\n");
    ASSERT_EQ(a7.count(), 1u);
    EXPECT_EQ(a7.replies[0].answer, PutAnswer::save);
    EXPECT_FALSE(a7.replies[0].always_from_device);
    // A second answer: a clear error, and the first stands.
    const Outcome again = run(puts_args({{"dismiss", "7"}}));
    EXPECT_EQ(again.code, 3);
    EXPECT_NE(again.err.find("no put 7 is waiting"), std::string::npos) << again.err;
    EXPECT_EQ(a7.count(), 1u);

    // --accept ID --open --always.
    const Outcome opened = run(puts_args({{"accept", "8"}}, {"open", "always"}));
    EXPECT_EQ(opened.code, 0) << opened.err;
    EXPECT_NE(opened.out.find("accepted, to be opened; its device's puts are accepted from now on"), std::string::npos)
        << opened.out;
    ASSERT_EQ(a8.count(), 1u);
    EXPECT_EQ(a8.replies[0].answer, PutAnswer::open);
    EXPECT_TRUE(a8.replies[0].always_from_device);

    // --dismiss ID.
    const Outcome dismissed = run(puts_args({{"dismiss", "9"}}));
    EXPECT_EQ(dismissed.code, 0) << dismissed.err;
    EXPECT_EQ(dismissed.out, "put 9 (report.pdf): dismissed\n");
    ASSERT_EQ(a9.count(), 1u);
    EXPECT_EQ(a9.replies[0].answer, PutAnswer::dismiss);
    EXPECT_TRUE(puts->pending().empty());

    // An id that never was.
    const Outcome unknown = run(puts_args({{"accept", "42"}}));
    EXPECT_EQ(unknown.code, 3);
    EXPECT_NE(unknown.err.find("no put 42 is waiting"), std::string::npos) << unknown.err;

    // A withdrawn offer is gone from the list and cannot be answered.
    ControlAnswers a10;
    puts->ask(control_file_offer(10), a10.callback());
    puts->withdraw(10);
    EXPECT_EQ(run(puts_args()).out, "no puts are waiting for an answer\n");
    EXPECT_EQ(run(puts_args({{"accept", "10"}})).code, 3);
    EXPECT_EQ(a10.count(), 0u);
}

TEST(PutControl, ClearErrorsWithoutAProviderOrWithWrongUsage) {
    TempDir runtime;
    ScopedEnv env("XDG_RUNTIME_DIR", runtime.path.string());
    const Outcome nobody = run(puts_args());
    EXPECT_EQ(nobody.code, 4);
    EXPECT_NE(nobody.err.find("no provider is running at"), std::string::npos) << nobody.err;
    EXPECT_TRUE(nobody.out.empty());

    using umf::cli::UsageError;
    EXPECT_THROW(run(puts_args({{"accept", "1"}, {"dismiss", "1"}})), UsageError);
    EXPECT_THROW(run(puts_args({}, {"open"})), UsageError);
    EXPECT_THROW(run(puts_args({{"dismiss", "1"}}, {"always"})), UsageError);
    EXPECT_THROW(run(puts_args({{"accept", "x"}})), UsageError);
    EXPECT_THROW(run(puts_args({{"accept", "0"}})), UsageError);
    auto words = puts_args();
    words.positional = {"7"};
    EXPECT_THROW(run(words), UsageError);
}

TEST(PutControl, RequestsWithoutPutsOrSharesAndMalformedAnswers) {
    SharedItems items;
    // A provider started with --puts always|never answers no put requests.
    const std::string no_puts = handle_control_request(R"({"cmd":"puts"})", &items, nullptr);
    EXPECT_NE(no_puts.find(R"("ok":false)"), std::string::npos);
    EXPECT_NE(no_puts.find("--puts always or never"), std::string::npos) << no_puts;
    EXPECT_EQ(handle_control_request(R"({"cmd":"list"})", items), R"({"items":[],"ok":true})");

    // In public mode: puts, but no shares.
    ControlPutDecider puts;
    EXPECT_EQ(handle_control_request(R"({"cmd":"puts"})", nullptr, &puts), R"({"ok":true,"puts":[]})");
    EXPECT_NE(handle_control_request(R"({"cmd":"list"})", nullptr, &puts).find("shares nothing"), std::string::npos);

    ControlAnswers answers;
    puts.ask(control_file_offer(3), answers.callback());
    for (const char* bad : {R"({"cmd":"put_answer","id":3})", R"({"cmd":"put_answer","id":3,"answer":"burn"})",
                            R"({"cmd":"put_answer","id":"3","answer":"save"})", R"({"cmd":"put_answer","id":-3,"answer":"save"})",
                            R"({"cmd":"put_answer","answer":"save"})", R"({"cmd":"put_answer","id":3,"answer":"save","always":1})",
                            R"({"cmd":"put_answer","id":3.5,"answer":"save"})"}) {
        const std::string answer = handle_control_request(bad, nullptr, &puts);
        EXPECT_EQ(answer.rfind(R"({"error":)", 0), 0u) << bad << " -> " << answer;
    }
    EXPECT_EQ(answers.count(), 0u) << "a malformed request answered";
    EXPECT_EQ(handle_control_request(R"({"cmd":"put_answer","id":3,"answer":"dismiss","always":true})", nullptr, &puts),
              R"({"answer":"dismiss","id":3,"name":"report.pdf","ok":true})");
    ASSERT_EQ(answers.count(), 1u);
    EXPECT_FALSE(answers.replies[0].always_from_device) << "a dismissal remembered the device";

    // A socket without shares still answers, and still counts as alive.
    TempDir dir;
    auto shared_puts = std::make_shared<ControlPutDecider>();
    ControlSocket socket(dir.path / "s" / "provider-2.sock", nullptr, shared_puts);
    EXPECT_EQ(control_request(socket.path(), R"({"cmd":"puts"})"), R"({"ok":true,"puts":[]})");
    EXPECT_THROW(ControlSocket(socket.path(), nullptr, shared_puts), std::runtime_error);
}

TEST(PutDeciders, TheFirstAnswerWinsAndTheOthersAreWithdrawn) {
    auto prompt = std::make_shared<ControlPutDecider>();  // stands in for the desktop prompt
    auto control = std::make_shared<ControlPutDecider>();
    FirstAnswerDecider first({prompt, control});
    ControlAnswers answers;
    first.ask(control_file_offer(1), answers.callback());
    ASSERT_EQ(prompt->pending().size(), 1u);
    ASSERT_EQ(control->pending().size(), 1u);
    ASSERT_TRUE(control->answer(1, PutReply{PutAnswer::open, true}));
    ASSERT_EQ(answers.count(), 1u);
    EXPECT_EQ(answers.replies[0].answer, PutAnswer::open);
    EXPECT_TRUE(answers.replies[0].always_from_device);
    EXPECT_TRUE(prompt->pending().empty()) << "the other question was not withdrawn";
    EXPECT_FALSE(prompt->answer(1, PutReply{PutAnswer::dismiss, false}));
    EXPECT_EQ(answers.count(), 1u);

    // withdraw reaches every decider.
    first.ask(control_file_offer(2), answers.callback());
    first.withdraw(2);
    EXPECT_TRUE(prompt->pending().empty());
    EXPECT_TRUE(control->pending().empty());
    EXPECT_EQ(answers.count(), 1u);
}

TEST(PutDeciders, AFixedAnswerWinsAtOnce) {
    ControlAnswers always;
    FixedPutDecider yes(PutAnswer::save);
    yes.ask(control_file_offer(1), always.callback());
    ASSERT_EQ(always.count(), 1u);
    EXPECT_EQ(always.replies[0].answer, PutAnswer::save);
    EXPECT_FALSE(always.replies[0].always_from_device);

    // First: the later deciders are never asked. Last: the earlier ones are withdrawn.
    auto control = std::make_shared<ControlPutDecider>();
    ControlAnswers a, b;
    FirstAnswerDecider fixed_first({std::make_shared<FixedPutDecider>(PutAnswer::dismiss), control});
    fixed_first.ask(control_file_offer(2), a.callback());
    ASSERT_EQ(a.count(), 1u);
    EXPECT_EQ(a.replies[0].answer, PutAnswer::dismiss);
    EXPECT_TRUE(control->pending().empty());
    FirstAnswerDecider fixed_last({control, std::make_shared<FixedPutDecider>(PutAnswer::save)});
    fixed_last.ask(control_file_offer(3), b.callback());
    ASSERT_EQ(b.count(), 1u);
    EXPECT_EQ(b.replies[0].answer, PutAnswer::save);
    EXPECT_TRUE(control->pending().empty());
}

TEST(PutDeciders, RacingAnswersPassOnExactlyOne) {
    for (int round = 0; round < 50; ++round) {
        std::vector<std::shared_ptr<ControlPutDecider>> controls;
        std::vector<std::shared_ptr<PutDecider>> deciders;
        for (int i = 0; i < 4; ++i) {
            controls.push_back(std::make_shared<ControlPutDecider>());
            deciders.push_back(controls.back());
        }
        auto first = std::make_shared<FirstAnswerDecider>(deciders);
        std::atomic<int> answered{0};
        first->ask(control_file_offer(1), [&](PutReply) { ++answered; });
        std::vector<std::thread> threads;
        std::atomic<int> taken{0};
        for (int i = 0; i < 4; ++i)
            threads.emplace_back([&, i] {
                if (controls[i]->answer(1, PutReply{PutAnswer::save, false})) ++taken;
            });
        for (auto& t : threads) t.join();
        EXPECT_EQ(answered.load(), 1);
        EXPECT_GE(taken.load(), 1);
        for (auto& c : controls) EXPECT_TRUE(c->pending().empty());
    }
}

TEST(PutFolder, TheXdgDownloadFolderElseDownloads) {
    const fs::path home = "/home/ana";
    EXPECT_EQ(download_dir_from_user_dirs("# comment\nXDG_DESKTOP_DIR=\"$HOME/Desktop\"\nXDG_DOWNLOAD_DIR=\"$HOME/Herunterladen\"\n",
                                          home),
              fs::path("/home/ana/Herunterladen"));
    EXPECT_EQ(download_dir_from_user_dirs("  XDG_DOWNLOAD_DIR=\"/data/in coming/\"  \n", home), fs::path("/data/in coming"));
    EXPECT_EQ(download_dir_from_user_dirs("XDG_DOWNLOAD_DIR=\"$HOME/a\\\"b\"\n", home), fs::path("/home/ana/a\"b"));
    // The last assignment counts.
    EXPECT_EQ(download_dir_from_user_dirs("XDG_DOWNLOAD_DIR=\"$HOME/one\"\nXDG_DOWNLOAD_DIR=\"$HOME/two\"\n", home),
              fs::path("/home/ana/two"));
    // Switched off (the home folder itself), relative, unquoted, commented out, absent.
    for (const char* text : {"XDG_DOWNLOAD_DIR=\"$HOME\"\n", "XDG_DOWNLOAD_DIR=\"$HOME/\"\n", "XDG_DOWNLOAD_DIR=\"Downloads\"\n",
                             "XDG_DOWNLOAD_DIR=$HOME/x\n", "# XDG_DOWNLOAD_DIR=\"$HOME/x\"\n", "XDG_MUSIC_DIR=\"$HOME/M\"\n", ""})
        EXPECT_EQ(download_dir_from_user_dirs(text, home), std::nullopt) << text;

    TempDir dir;
    ScopedEnv home_env("HOME", (dir.path / "home").string());
    ScopedEnv config_env("XDG_CONFIG_HOME", (dir.path / "config").string());
    EXPECT_EQ(default_put_folder(), dir.path / "home" / "Downloads");
    fs::create_directories(dir.path / "config");
    std::ofstream(dir.path / "config" / "user-dirs.dirs") << "XDG_DOWNLOAD_DIR=\"$HOME/Téléchargements\"\n";
    EXPECT_EQ(default_put_folder(), dir.path / "home" / "Téléchargements");
}

TEST(PutText, SizesHostsSummariesAndPrintableText) {
    EXPECT_EQ(human_size(0), "0 bytes");
    EXPECT_EQ(human_size(1), "1 byte");
    EXPECT_EQ(human_size(1023), "1023 bytes");
    EXPECT_EQ(human_size(1024), "1.0 KB");
    EXPECT_EQ(human_size(48213), "47 KB");
    EXPECT_EQ(human_size(2411724), "2.3 MB");
    EXPECT_EQ(human_size(1024 * 1024 - 1), "1.0 MB");
    EXPECT_EQ(human_size(std::int64_t{4} << 30), "4.0 GB");

    EXPECT_EQ(put_url_host("https://user:pw@Example.org:8443/a?b#c"), "Example.org");
    EXPECT_EQ(put_url_host("http://[::1]:80/x"), "[::1]");
    EXPECT_EQ(put_url_host("https://example.org"), "example.org");
    EXPECT_EQ(put_url_host("not a url"), "not a url");

    EXPECT_EQ(put_offer_summary(control_file_offer(1)), "Incoming: report.pdf, 2.3 MB, from Pixel 7");
    PutOffer u = control_url_offer(2);
    EXPECT_EQ(put_offer_summary(u), "Incoming: Talk page (https://example.org/talk), from umf-web/0.1 (Android; Chrome 120)");
    u.title.clear();
    u.client.clear();
    EXPECT_EQ(put_offer_summary(u), "Incoming: example.org (https://example.org/talk)");

    EXPECT_EQ(printable_text("a\x1b[2Jb\nc\x7f"), "a?[2Jb?c?");
    EXPECT_EQ(printable_text("r\u00e9sum\u00e9.pdf"), "r\u00e9sum\u00e9.pdf");
    EXPECT_EQ(printable_text("invoice\u202Efdp.exe"), "invoice?fdp.exe");
    EXPECT_EQ(printable_text("x\xc2\x9b" "1m"), "x?1m");  // C1 CSI
    EXPECT_EQ(printable_text("bad\xff\xfe"), "bad??");
}

}  // namespace

#endif  // UMF_PROVIDER_TESTS
