// The put prompt (provider/put/put_prompt_window.hpp) on the offscreen
// platform: what a card says, how it grows with a long name and stays on the
// screen, where its buttons are and what clicks there answer, the toggle,
// the countdown and the card's own dismissal, withdrawal, cards stacking
// without overlap, and offers handed over from another thread.
#if defined(UMF_PROVIDER_TESTS)

#include <gtest/gtest.h>

#include <QGuiApplication>
#include <QImage>
#include <QMouseEvent>
#include <QPainter>
#include <QScreen>
#include <atomic>
#include <mutex>
#include <thread>
#include <vector>

#include "provider/put/put_prompt_window.hpp"
#include "provider/put/put_text.hpp"
#include "tests/provider/gui_test_app.hpp"
#include "tests/provider/qt_pump.hpp"

namespace {

using namespace umf::provider;

}  // namespace

// Readable failures for QString comparisons.
QT_BEGIN_NAMESPACE
inline void PrintTo(const QString& s, std::ostream* os) { *os << '"' << s.toStdString() << '"'; }
QT_END_NAMESPACE

namespace {

using namespace umf::provider;
using umf::test::pump_until;
using Part = PutCard::Part;

PutOffer file_offer(std::uint64_t id, std::string name = "report.pdf") {
    PutOffer o;
    o.id = id;
    o.client = "Pixel 7";
    o.device = "d-4f2a";
    o.kind = umf::protocol::ContentKind::file;
    o.name = std::move(name);
    o.mime = "application/pdf";
    o.size = 2411724;
    return o;
}

PutOffer url_offer(std::uint64_t id, std::string title = "Talk page") {
    PutOffer o;
    o.id = id;
    o.client = "Pixel 7";
    o.kind = umf::protocol::ContentKind::url;
    o.url = "https://example.org/talks/2024/a-rather-long-path/that-goes-on?and=on&on=and#on";
    o.title = std::move(title);
    return o;
}

PutCard::Clock::time_point in_seconds(int s) { return PutCard::Clock::now() + std::chrono::seconds(s); }

QImage render(PutCard& card) {
    QImage image(card.size(), QImage::Format_ARGB32_Premultiplied);
    image.fill(Qt::transparent);
    QPainter painter(&image);
    card.paint_to(painter);
    return image;
}

// Pixels of `image` within `rect` that differ from the card's background
// (sampled just inside the top-left corner's straight edge).
int ink(const QImage& image, const QRect& rect) {
    const QRgb background = image.pixel(image.width() / 2, 2);
    int n = 0;
    for (int y = rect.top(); y <= rect.bottom(); ++y)
        for (int x = rect.left(); x <= rect.right(); ++x)
            if (image.rect().contains(x, y) && image.pixel(x, y) != background) ++n;
    return n;
}

void click_at(PutCard* card, QPointF at, Qt::MouseButton button = Qt::LeftButton) {
    QMouseEvent press(QEvent::MouseButtonPress, at, card->mapToGlobal(at), button, button, Qt::NoModifier);
    QCoreApplication::sendEvent(card, &press);
    QMouseEvent release(QEvent::MouseButtonRelease, at, card->mapToGlobal(at), button, Qt::NoButton, Qt::NoModifier);
    QCoreApplication::sendEvent(card, &release);
}

void click(PutCard* card, Part part) { click_at(card, QRectF(card->part_rect(part)).center()); }

// The answers a decider gave, as the service would receive them.
struct PromptAnswers {
    std::mutex mutex;
    std::vector<PutReply> replies;
    std::vector<std::thread::id> threads;
    std::function<void(PutReply)> callback() {
        return [this](PutReply r) {
            std::lock_guard lock(mutex);
            replies.push_back(r);
            threads.push_back(std::this_thread::get_id());
        };
    }
    std::size_t count() {
        std::lock_guard lock(mutex);
        return replies.size();
    }
};

TEST(PutPrompt, AFileCardSaysWhatComesFromWhomWithThreeButtonsAndTheToggle) {
    umf::test::ensure_gui_application();
    PutCard card(file_offer(1), QGuiApplication::primaryScreen(), in_seconds(30), {});
    EXPECT_EQ(put_offer_summary(card.offer()), "Incoming: report.pdf, 2.3 MB, from Pixel 7");
    ASSERT_EQ(card.lines().size(), 2);
    EXPECT_EQ(card.lines()[0], "Incoming: report.pdf");
    EXPECT_EQ(card.lines()[1], "2.3 MB, from Pixel 7");
    EXPECT_EQ(card.countdown_text(), "Dismissing in 30 s");
    for (Part p : {Part::open, Part::save, Part::dismiss, Part::always}) {
        const QRect r = card.part_rect(p);
        EXPECT_FALSE(r.isEmpty());
        EXPECT_TRUE(QRect(QPoint(), card.size()).contains(r)) << "part outside the card";
        EXPECT_EQ(card.part_at(QRectF(r).center()), p);
    }
    // Buttons in a row, left to right, not overlapping; the toggle above them.
    EXPECT_LT(card.part_rect(Part::open).right(), card.part_rect(Part::save).left());
    EXPECT_LT(card.part_rect(Part::save).right(), card.part_rect(Part::dismiss).left());
    EXPECT_LT(card.part_rect(Part::always).bottom(), card.part_rect(Part::save).top());
    EXPECT_EQ(card.part_at(QPointF(2, 2)), Part::none);

    // Takes clicks, never the focus.
    EXPECT_FALSE(card.flags() & Qt::WindowTransparentForInput);
    EXPECT_TRUE(card.flags() & Qt::WindowDoesNotAcceptFocus);
    EXPECT_TRUE(card.flags() & Qt::WindowStaysOnTopHint);

    // Drawn: ink in the text lines and on the buttons; another name draws
    // another headline, the same details.
    const QImage image = render(card);
    const QRect headline(12, 12, card.width() - 24, card.part_rect(Part::always).top() - 12);
    EXPECT_GT(ink(image, headline), 50);
    EXPECT_GT(ink(image, card.part_rect(Part::save)), 50);
    PutCard other(file_offer(2, "minutes.odt"), QGuiApplication::primaryScreen(), in_seconds(30), {});
    EXPECT_EQ(other.lines()[1], card.lines()[1]);
    const QImage other_image = render(other);
    const int top = 12, rows = QFontMetrics(QFont()).height();
    bool differs = false;
    for (int y = top; y < top + rows && !differs; ++y)
        for (int x = 12; x < std::min(image.width(), other_image.width()) - 12 && !differs; ++x)
            differs = image.pixel(x, y) != other_image.pixel(x, y);
    EXPECT_TRUE(differs) << "the headline did not change with the name";
}

TEST(PutPrompt, AUrlCardShowsTitleOrHostAndTheUrlWithOpenAndDismiss) {
    umf::test::ensure_gui_application();
    PutCard titled(url_offer(1), QGuiApplication::primaryScreen(), in_seconds(30), {});
    ASSERT_EQ(titled.lines().size(), 3);
    EXPECT_EQ(titled.lines()[0], "Incoming: Talk page");
    EXPECT_TRUE(titled.lines()[1].startsWith("https://example.org/"));
    EXPECT_EQ(titled.lines()[2], "from Pixel 7");
    EXPECT_FALSE(titled.part_rect(Part::open).isEmpty());
    EXPECT_FALSE(titled.part_rect(Part::dismiss).isEmpty());
    EXPECT_TRUE(titled.part_rect(Part::save).isEmpty());
    EXPECT_TRUE(titled.part_rect(Part::always).isEmpty()) << "no device, no toggle";

    PutCard untitled(url_offer(2, ""), QGuiApplication::primaryScreen(), in_seconds(30), {});
    EXPECT_EQ(untitled.lines()[0], "Incoming: example.org");
    // Too long for the card: elided in the middle, keeping both ends.
    PutOffer long_url = url_offer(3);
    long_url.url = "https://example.org/" + std::string(600, 'x') + "/end.html";
    PutCard elided(long_url, QGuiApplication::primaryScreen(), in_seconds(30), {});
    EXPECT_LE(elided.width(), PutCard::kMaxWidth);
    EXPECT_TRUE(elided.lines()[1].startsWith("https://ex"));
    EXPECT_TRUE(elided.lines()[1].endsWith("end.html"));
    EXPECT_TRUE(elided.lines()[1].contains(QChar(0x2026)));
}

TEST(PutPrompt, ALongNameGrowsTheCardWithinTheScreenKeepingTheExtension) {
    umf::test::ensure_gui_application();
    QScreen* screen = QGuiApplication::primaryScreen();
    PutCard short_name(file_offer(1, "a.pdf"), screen, in_seconds(30), {});
    PutCard longer(file_offer(2, "quarterly report, final version.pdf"), screen, in_seconds(30), {});
    PutCard huge(file_offer(3, std::string(400, 'n') + ".pdf"), screen, in_seconds(30), {});
    EXPECT_LT(short_name.width(), longer.width());
    EXPECT_EQ(longer.lines()[0].toStdString(), "Incoming: quarterly report, final version.pdf");
    EXPECT_LE(huge.width(), PutCard::kMaxWidth);
    EXPECT_LE(huge.width(), screen->geometry().width() - 2 * PutCard::kScreenMargin);
    EXPECT_TRUE(huge.lines()[0].startsWith("Incoming: nnn"));
    EXPECT_TRUE(huge.lines()[0].endsWith("nn.pdf")) << huge.lines()[0].toStdString();
    // The buttons still fit.
    EXPECT_LE(huge.part_rect(Part::dismiss).right(), huge.width());
}

TEST(PutPrompt, RequesterTextCannotSpoofTheCard) {
    umf::test::ensure_gui_application();
    PutOffer o = file_offer(1, "invoice\u202Efdp.exe");
    o.client = "Pixel\n7\x1b[31m";
    PutCard card(o, QGuiApplication::primaryScreen(), in_seconds(30), {});
    EXPECT_FALSE(card.lines()[0].contains(QChar(0x202E)));
    EXPECT_FALSE(card.lines()[1].contains(QChar('\n')));
    EXPECT_FALSE(card.lines()[1].contains(QChar(0x1b)));
}

TEST(PutPrompt, ClicksOnTheButtonsAnswerOnce) {
    umf::test::ensure_gui_application();
    PutPromptDecider decider(std::chrono::seconds(30));
    PromptAnswers save, dismiss, open;
    decider.ask(file_offer(1), save.callback());
    decider.ask(file_offer(2), dismiss.callback());
    decider.ask(file_offer(3), open.callback());
    ASSERT_TRUE(pump_until([&] { return decider.cards().size() == 3; }, 3000));

    PutCard* card = decider.card(1);
    click(card, Part::save);
    click(card, Part::save);  // the card is still there until the loop runs: no second answer
    ASSERT_EQ(save.count(), 1u);
    EXPECT_EQ(save.replies[0].answer, PutAnswer::save);
    EXPECT_FALSE(save.replies[0].always_from_device);
    EXPECT_EQ(save.threads[0], std::this_thread::get_id()) << "answered off the Qt thread";
    EXPECT_EQ(decider.card(1), nullptr);

    click(decider.card(2), Part::dismiss);
    ASSERT_EQ(dismiss.count(), 1u);
    EXPECT_EQ(dismiss.replies[0].answer, PutAnswer::dismiss);

    // Pressed on Open, released on Dismiss: nothing; the right button: nothing.
    card = decider.card(3);
    QMouseEvent press(QEvent::MouseButtonPress, QRectF(card->part_rect(Part::open)).center(), QPointF(), Qt::LeftButton,
                      Qt::LeftButton, Qt::NoModifier);
    QCoreApplication::sendEvent(card, &press);
    QMouseEvent release(QEvent::MouseButtonRelease, QRectF(card->part_rect(Part::dismiss)).center(), QPointF(),
                        Qt::LeftButton, Qt::NoButton, Qt::NoModifier);
    QCoreApplication::sendEvent(card, &release);
    click_at(card, QRectF(card->part_rect(Part::open)).center(), Qt::RightButton);
    EXPECT_EQ(open.count(), 0u);
    click(card, Part::open);
    ASSERT_EQ(open.count(), 1u);
    EXPECT_EQ(open.replies[0].answer, PutAnswer::open);
    EXPECT_TRUE(pump_until([&] { return decider.cards().empty(); }, 1000));
}

TEST(PutPrompt, TheToggleAcceptsTheDeviceFromNowOn) {
    umf::test::ensure_gui_application();
    PutPromptDecider decider(std::chrono::seconds(30));
    PromptAnswers always, twice, refused;
    decider.ask(file_offer(1), always.callback());
    decider.ask(file_offer(2), twice.callback());
    decider.ask(file_offer(3), refused.callback());
    ASSERT_TRUE(pump_until([&] { return decider.cards().size() == 3; }, 3000));

    PutCard* card = decider.card(1);
    EXPECT_FALSE(card->always());
    click(card, Part::always);
    EXPECT_TRUE(card->always());
    EXPECT_EQ(always.count(), 0u) << "the toggle answered";
    click(card, Part::save);
    ASSERT_EQ(always.count(), 1u);
    EXPECT_TRUE(always.replies[0].always_from_device);

    card = decider.card(2);
    click(card, Part::always);
    click(card, Part::always);
    click(card, Part::open);
    ASSERT_EQ(twice.count(), 1u);
    EXPECT_FALSE(twice.replies[0].always_from_device);

    // Dismissing never remembers the device.
    card = decider.card(3);
    click(card, Part::always);
    click(card, Part::dismiss);
    ASSERT_EQ(refused.count(), 1u);
    EXPECT_FALSE(refused.replies[0].always_from_device);
}

TEST(PutPrompt, WithdrawTakesTheCardDownWithoutAnAnswer) {
    umf::test::ensure_gui_application();
    PutPromptDecider decider(std::chrono::seconds(30));
    PromptAnswers answers;
    decider.ask(file_offer(5), answers.callback());
    decider.ask(url_offer(6), answers.callback());
    ASSERT_TRUE(pump_until([&] { return decider.cards().size() == 2; }, 3000));
    EXPECT_TRUE(decider.card(5)->isVisible());
    decider.withdraw(5);
    decider.withdraw(77);  // unknown: nothing
    ASSERT_TRUE(pump_until([&] { return decider.cards().size() == 1; }, 3000));
    EXPECT_EQ(decider.card(5), nullptr);
    EXPECT_NE(decider.card(6), nullptr);
    EXPECT_EQ(answers.count(), 0u);
}

TEST(PutPrompt, TheCountdownRunsDownAndTheCardDismissesItself) {
    umf::test::ensure_gui_application();
    PutPromptDecider decider(std::chrono::seconds(2));
    PromptAnswers answers;
    decider.ask(file_offer(1), answers.callback());
    ASSERT_TRUE(pump_until([&] { return decider.card(1) != nullptr; }, 3000));
    PutCard* card = decider.card(1);
    EXPECT_EQ(card->seconds_left(), 2);
    EXPECT_EQ(card->countdown_text(), "Dismissing in 2 s");
    pump_until([] { return false; }, 1200);
    ASSERT_EQ(decider.card(1), card);
    EXPECT_EQ(card->seconds_left(), 1);
    EXPECT_EQ(card->countdown_text(), "Dismissing in 1 s");
    ASSERT_TRUE(pump_until([&] { return answers.count() == 1; }, 3000));
    EXPECT_EQ(answers.replies[0].answer, PutAnswer::dismiss);
    EXPECT_TRUE(decider.cards().empty());
}

TEST(PutPrompt, CardsSitBesideThePointInsideTheScreenAndStackWithoutOverlap) {
    umf::test::ensure_gui_application();
    QScreen* screen = QGuiApplication::primaryScreen();
    const QRect area = screen->geometry();
    const double dpr = screen->devicePixelRatio();
    PutPromptDecider decider(std::chrono::seconds(30));
    PromptAnswers answers;
    // Three offers at one point, one at the bottom-right corner, one without a point.
    const QPointF point(120 * dpr, 90 * dpr), corner((area.width() - 5) * dpr, (area.height() - 5) * dpr);
    for (std::uint64_t id = 1; id <= 5; ++id) {
        PutOffer o = id % 2 ? file_offer(id) : url_offer(id);
        if (id <= 3) o.at = ScreenPoint{0, point.x(), point.y(), point.x(), point.y()};
        else if (id == 4) o.at = ScreenPoint{0, corner.x(), corner.y(), corner.x(), corner.y()};
        decider.ask(o, answers.callback());
    }
    ASSERT_TRUE(pump_until([&] { return decider.cards().size() == 5; }, 3000));
    const QPoint logical_point = area.topLeft() + (point / dpr).toPoint();
    const QPoint logical_corner = area.topLeft() + (corner / dpr).toPoint();
    // The first card just below right of the point, the point itself clear.
    const QRect first = decider.card(1)->geometry();
    EXPECT_GT(first.left(), logical_point.x());
    EXPECT_GT(first.top(), logical_point.y());
    EXPECT_LT(first.left() - logical_point.x(), 60);
    EXPECT_LT(first.top() - logical_point.y(), 60);
    // At the corner: turned to the left and above, the point clear.
    EXPECT_LT(decider.card(4)->geometry().right(), logical_corner.x());
    EXPECT_LT(decider.card(4)->geometry().bottom(), logical_corner.y());

    const auto cards = decider.cards();
    for (std::size_t i = 0; i < cards.size(); ++i) {
        const QRect a = cards[i]->geometry();
        EXPECT_TRUE(area.contains(a)) << "card " << i << " leaves the screen";
        for (std::size_t j = i + 1; j < cards.size(); ++j)
            EXPECT_FALSE(a.intersects(cards[j]->geometry())) << "cards " << i << " and " << j << " overlap";
    }
}

TEST(PutPrompt, PlacementKeepsToTheScreenAndFallsBackToACascade) {
    const QRect screen(1920, 0, 1280, 800);
    const QSize size(300, 120);
    const QRect beside = place_put_card(size, QPointF(1920 + 100, 100), screen, {});
    EXPECT_EQ(beside.topLeft(), QPoint(1920 + 128, 128));
    // Left of and above a point at the far corner.
    const QRect turned = place_put_card(size, QPointF(1920 + 1270, 790), screen, {});
    EXPECT_EQ(turned.bottomRight(), QPoint(1920 + 1270 - 28 - 1, 790 - 28 - 1));
    // A second card below the first.
    const QRect second = place_put_card(size, QPointF(1920 + 100, 100), screen, {beside});
    EXPECT_FALSE(second.intersects(beside));
    EXPECT_TRUE(screen.contains(second));
    // Larger than the screen: cut to it.
    const QRect big = place_put_card(QSize(5000, 5000), std::nullopt, screen, {});
    EXPECT_TRUE(screen.contains(big));
    // Without a point: centred.
    const QRect centred = place_put_card(size, std::nullopt, screen, {});
    EXPECT_LE(std::abs(centred.center().x() - screen.center().x()), 1);
    EXPECT_LE(std::abs(centred.center().y() - screen.center().y()), 1);
    // No free place left: still on the screen.
    std::vector<QRect> full{screen};
    EXPECT_TRUE(screen.contains(place_put_card(size, std::nullopt, screen, full)));
}

TEST(PutPrompt, OffersFromAServerThreadReachTheQtThread) {
    umf::test::ensure_gui_application();
    PutPromptDecider decider(std::chrono::seconds(30));
    PromptAnswers answers;
    std::vector<std::thread> threads;
    for (std::uint64_t id = 1; id <= 4; ++id)
        threads.emplace_back([&, id] { decider.ask(file_offer(id), answers.callback()); });
    for (auto& t : threads) t.join();
    ASSERT_TRUE(pump_until([&] { return decider.cards().size() == 4; }, 3000));
    std::thread([&] { decider.withdraw(2); }).join();
    ASSERT_TRUE(pump_until([&] { return decider.cards().size() == 3; }, 3000));
    click(decider.card(3), Part::save);
    ASSERT_EQ(answers.count(), 1u);
    EXPECT_EQ(answers.threads[0], std::this_thread::get_id());
}

TEST(PutPrompt, CardsStepAsideForASnapshotAndComeBack) {
    umf::test::ensure_gui_application();
    PutPromptDecider decider(std::chrono::seconds(2));
    PromptAnswers answers;
    decider.ask(file_offer(1), answers.callback());
    ASSERT_TRUE(pump_until([&] { return decider.card(1) != nullptr; }, 3000));
    EXPECT_TRUE(decider.card(1)->isVisible());
    // Nested, as a snapshot during the overlay's own grab can be.
    decider.hide_for_snapshot();
    decider.hide_for_snapshot();
    EXPECT_FALSE(decider.card(1)->isVisible());
    // A put asked about meanwhile waits unseen.
    decider.ask(url_offer(2), answers.callback());
    ASSERT_TRUE(pump_until([&] { return decider.card(2) != nullptr; }, 3000));
    EXPECT_FALSE(decider.card(2)->isVisible());
    decider.show_after_snapshot();
    EXPECT_FALSE(decider.card(1)->isVisible()) << "the outer snapshot is still being taken";
    decider.show_after_snapshot();
    EXPECT_TRUE(decider.card(1)->isVisible());
    EXPECT_TRUE(decider.card(2)->isVisible());
    decider.show_after_snapshot();  // one too many: no harm, and the next hide still hides
    decider.hide_for_snapshot();
    EXPECT_FALSE(decider.card(2)->isVisible());
    // The countdown goes on while hidden: the card dismisses the put in time.
    ASSERT_TRUE(pump_until([&] { return answers.count() == 2; }, 4000));
    EXPECT_EQ(answers.replies[0].answer, PutAnswer::dismiss);
    decider.show_after_snapshot();
    EXPECT_TRUE(decider.cards().empty());
}

}  // namespace

#endif  // UMF_PROVIDER_TESTS
