// The provider's console lines about requesters: one a welcome, a grab, a
// put's step and a departure, text from requesters made harmless for a terminal, and every
// call passed on to the listener behind.
#ifdef UMF_PROVIDER_TESTS

#include <gtest/gtest.h>

#include <sstream>

#include "provider/service/console_activity.hpp"

namespace {

using namespace umf::provider;

struct Counting : ActivityListener {
    int welcomes = 0, seekings = 0, aims = 0, grabs = 0, puts = 0, lefts = 0;
    void welcomed(const WelcomeActivity&) override { ++welcomes; }
    void seeking(std::uint64_t) override { ++seekings; }
    void aimed(const AimActivity&) override { ++aims; }
    void grabbed(const GrabActivity&) override { ++grabs; }
    void put(const PutActivity&) override { ++puts; }
    void left(std::uint64_t) override { ++lefts; }
};

TEST(ConsoleActivity, OneLineForEachWelcomeGrabAndDeparture) {
    std::ostringstream out;
    auto next = std::make_shared<Counting>();
    ConsoleActivity console(out, next);
    console.welcomed({7, "umf-web/0.1 (Android)", "192.168.1.5"});
    console.seeking(7);
    console.aimed({});
    console.grabbed({7, umf::protocol::ContentKind::file, "Q3 report", "report.pdf", 48213});
    console.grabbed({7, umf::protocol::ContentKind::url, "Project site", "", 0});
    console.left(7);
    EXPECT_EQ(out.str(),
              "requester 7 connected: umf-web/0.1 (Android) from 192.168.1.5\n"
              "requester 7 took \"Q3 report\" (file report.pdf, 48213 bytes)\n"
              "requester 7 took \"Project site\" (url)\n"
              "requester 7 left\n");
    EXPECT_EQ(next->welcomes, 1);
    EXPECT_EQ(next->seekings, 1);
    EXPECT_EQ(next->aims, 1);
    EXPECT_EQ(next->grabs, 2);
    EXPECT_EQ(next->lefts, 1);
}

TEST(ConsoleActivity, ARefusedHelloSaysWhoAndWhy) {
    std::ostringstream out;
    auto next = std::make_shared<Counting>();
    ConsoleActivity console(out, next);
    console.refused({"umf-web/0.1 (Android)", "Pixel 7", "192.168.1.5", false});
    console.refused({"", "", "192.168.1.6", true});
    console.refused({"\x1b[31mred", "", "", false});
    EXPECT_EQ(out.str(),
              "requester \"umf-web/0.1 (Android)\" (\"Pixel 7\") from 192.168.1.5 refused: its pairing token is not "
              "this provider's (pair it again: scan the QR code, or umf-provider pair)\n"
              "a requester from 192.168.1.6 refused: too many wrong pairing tokens from its address; refusing it for "
              "a minute\n"
              "requester \"?[31mred\" refused: its pairing token is not this provider's (pair it again: scan the QR "
              "code, or umf-provider pair)\n");
}

TEST(ConsoleActivity, RequesterTextCannotDriveTheTerminal) {
    std::ostringstream out;
    ConsoleActivity console(out, nullptr);
    console.welcomed({1, "evil\x1b]0;owned\x07\x1b[2J\nfake line", "::1"});
    const std::string text = out.str();
    EXPECT_EQ(text.find('\x1b'), std::string::npos);
    EXPECT_EQ(text.find('\x07'), std::string::npos);
    EXPECT_EQ(std::count(text.begin(), text.end(), '\n'), 1);
    EXPECT_EQ(printable(std::string(300, 'a')).size(), 131u);  // 128 and an ellipsis
}

TEST(ConsoleActivity, OneLineForEachStepOfAPut) {
    std::ostringstream out;
    auto next = std::make_shared<Counting>();
    ConsoleActivity console(out, next);
    PutActivity file;
    file.session = 3;
    file.kind = umf::protocol::ContentKind::file;
    file.name = "report.pdf";
    file.size = 2411724;
    file.client = "Pixel 7 (umf web, Android)";
    file.device = "umf-web-1dd5e5b3a0c4f9e2";
    file.stage = PutStage::asking;
    console.put(file);
    file.stage = PutStage::accepted;
    file.asked = true;
    file.answer = "open";
    file.always = true;
    console.put(file);
    file.stage = PutStage::opened;
    file.path = "/home/ana/Downloads/report (1).pdf";
    console.put(file);
    PutActivity url;
    url.session = 4;
    url.kind = umf::protocol::ContentKind::url;
    url.url = "https://example.org/talk";
    url.stage = PutStage::accepted;
    url.answer = "open";
    url.trusted = true;
    console.put(url);
    url.stage = PutStage::refused;
    url.asked = true;
    url.detail = "declined at the screen";
    console.put(url);
    EXPECT_EQ(out.str(),
              "requester 3 puts file \"report.pdf\" (2411724 bytes) from \"Pixel 7 (umf web, Android)\": asking the screen\n"
              "requester 3's put \"report.pdf\": accepted (open, always from now on)\n"
              "requester 3 put report.pdf (2411724 bytes) \u2192 saved as /home/ana/Downloads/report (1).pdf and "
              "opened\n"
              "requester 4 puts url <https://example.org/talk>: accepted (open, a device always accepted)\n"
              "requester 4's put \"https://example.org/talk\": refused (declined at the screen)\n");
    EXPECT_EQ(next->puts, 5);
}

TEST(ConsoleActivity, PrintableHidesBidiOverridesAndCutsWholeCharacters) {
    // U+202E would show "invoice\u202Efdp.exe" as "invoiceexe.pdf".
    EXPECT_EQ(printable("invoice\xe2\x80\xae" "fdp.exe"), "invoice?fdp.exe");
    EXPECT_EQ(printable("a\xc2\x9b" "31m"), "a?31m") << "C1 control sequence introducer";
    // Three-byte characters cut at 4 bytes: one whole character and the ellipsis.
    EXPECT_EQ(printable("\xe2\x82\xac\xe2\x82\xac", 4), "\xe2\x82\xac...");
    EXPECT_EQ(printable("caf\xc3\xa9"), "caf\xc3\xa9");
}

}  // namespace

#endif
