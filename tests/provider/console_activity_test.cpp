// The provider's console lines about requesters: one a welcome, a grab and a
// departure, text from requesters made harmless for a terminal, and every
// call passed on to the listener behind.
#ifdef UMF_PROVIDER_TESTS

#include <gtest/gtest.h>

#include <sstream>

#include "server/console_activity.hpp"

namespace {

using namespace umf::provider;

struct Counting : ActivityListener {
    int welcomes = 0, seekings = 0, aims = 0, grabs = 0, lefts = 0;
    void welcomed(const WelcomeActivity&) override { ++welcomes; }
    void seeking(std::uint64_t) override { ++seekings; }
    void aimed(const AimActivity&) override { ++aims; }
    void grabbed(const GrabActivity&) override { ++grabs; }
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

}  // namespace

#endif
