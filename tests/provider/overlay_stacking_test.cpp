// The put cards stay over the field on a real X server, in every restack:
// the field raises itself over new windows once a second, and a compositor
// draws whatever stacking the server has between two requests. Another
// client watches the root window's children (SubstructureNotify) and
// replays each restack, map and unmap; after every one of them each card
// shown lies above the field's window and the aim ring's. Then, at rest, the
// field is back over a window mapped since, and the card over the ring.
//
// The Qt half runs in a child process (tests/provider/x11_child.hpp).
#if defined(UMF_PROVIDER_TESTS) && defined(UMF_PROVIDER_OVERLAY)

#include <gtest/gtest.h>

#include <QElapsedTimer>
#include <QGuiApplication>
#include <QPainter>
#include <QRasterWindow>
#include <algorithm>
#include <cstdlib>
#include <functional>
#include <map>
#include <set>
#include <string>
#include <thread>
#include <vector>

#include "provider/desktop/x11/overlay_window.hpp"
#include "provider/field_overlay/overlay_manager.hpp"
#include "provider/put/put_prompt_window.hpp"
#include "tests/provider/x11_child.hpp"

// Last: Xlib's macros clash with Qt's headers.
#include <X11/Xlib.h>

namespace {

using namespace umf::provider;
using namespace umf::test;

// The root window's children bottom to top, as another client sees them,
// kept from the events the server sends it.
class StackWatch {
public:
    explicit StackWatch(const std::string& display_name) : display_(XOpenDisplay(display_name.c_str())) {
        if (!display_) return;
        root_ = DefaultRootWindow(display_);
        XSelectInput(display_, root_, SubstructureNotifyMask);
        ::Window root = 0, parent = 0, *children = nullptr;
        unsigned count = 0;
        if (XQueryTree(display_, root_, &root, &parent, &children, &count)) {
            order_.assign(children, children + count);
            XFree(children);
        }
        for (::Window w : order_) {
            XWindowAttributes a;
            if (XGetWindowAttributes(display_, w, &a) && a.map_state != IsUnmapped) mapped_.insert(w);
        }
    }
    ~StackWatch() {
        if (display_) XCloseDisplay(display_);
    }
    StackWatch(const StackWatch&) = delete;
    StackWatch& operator=(const StackWatch&) = delete;

    bool ok() const { return display_ != nullptr; }
    // The events queued so far, each applied and then `after` called.
    void drain(const std::function<void(const StackWatch&, const std::string&)>& after) {
        while (XPending(display_)) {
            XEvent e;
            XNextEvent(display_, &e);
            if (const std::string what = apply(e); !what.empty()) after(*this, what);
        }
    }
    // Bottom 0; -1: not a child of the root.
    int position(unsigned long window) const {
        const auto it = std::find(order_.begin(), order_.end(), window);
        return it == order_.end() ? -1 : static_cast<int>(it - order_.begin());
    }
    bool mapped(unsigned long window) const { return mapped_.count(window) > 0; }
    // The ConfigureNotify events seen for `window`.
    int restacks(unsigned long window) const {
        const auto it = restacks_.find(window);
        return it == restacks_.end() ? 0 : it->second;
    }
    // The root's child that holds `window` (its frame, once a window
    // manager has reparented it).
    unsigned long top_level(unsigned long window) const {
        for (;;) {
            ::Window root = 0, parent = 0, *children = nullptr;
            unsigned count = 0;
            if (!XQueryTree(display_, window, &root, &parent, &children, &count)) return 0;
            if (children) XFree(children);
            if (parent == root_) return window;
            window = parent;
        }
    }

private:
    void erase(::Window w) { order_.erase(std::remove(order_.begin(), order_.end(), w), order_.end()); }
    std::string apply(const XEvent& e) {
        switch (e.type) {
        case CreateNotify:
            if (e.xcreatewindow.parent != root_) return {};
            order_.push_back(e.xcreatewindow.window);
            return "create";
        case DestroyNotify:
            erase(e.xdestroywindow.window);
            mapped_.erase(e.xdestroywindow.window);
            return "destroy";
        case ReparentNotify:
            erase(e.xreparent.window);
            if (e.xreparent.parent == root_) order_.push_back(e.xreparent.window);
            return "reparent";
        case MapNotify:
            mapped_.insert(e.xmap.window);
            return "map";
        case UnmapNotify:
            mapped_.erase(e.xunmap.window);
            return "unmap";
        case ConfigureNotify: {
            if (e.xconfigure.event != root_) return {};
            ++restacks_[e.xconfigure.window];
            erase(e.xconfigure.window);
            const auto below = std::find(order_.begin(), order_.end(), e.xconfigure.above);
            order_.insert(e.xconfigure.above == None || below == order_.end() ? order_.begin() : below + 1,
                          e.xconfigure.window);
            return "restack";
        }
        default:
            return {};
        }
    }

    Display* display_ = nullptr;
    ::Window root_ = 0;
    std::vector<::Window> order_;
    std::set<::Window> mapped_;
    std::map<::Window, int> restacks_;
};

// A window of another program: managed, framed by openbox, mapped on top.
class Plain : public QRasterWindow {
protected:
    void paintEvent(QPaintEvent*) override { QPainter(this).fillRect(QRect(QPoint(), size()), Qt::gray); }
};

TEST(OverlayStackingOnX, DISABLED_Child) {
    if (!std::getenv(kX11ChildVariable)) GTEST_SKIP() << "run by OverlayStacking.ThePutCardStaysOverTheFieldInEveryRestack";
    X11ChildApplication child;
    ASSERT_EQ(QGuiApplication::platformName(), "xcb");
    StackWatch watch(std::getenv("DISPLAY"));
    ASSERT_TRUE(watch.ok());

    umf::overlay::Preset preset;
    preset.opacity_min = 0.3;
    preset.opacity_max = 0.5;
    preset.activation = umf::overlay::Activation::always;
    OverlayManager manager(preset);
    PutPromptDecider cards(std::chrono::seconds(60));
    // As the provider wires them (commands/serve_parts.cpp).
    manager.set_windows_over_field([&] { return cards.shown_cards(); });
    ASSERT_EQ(manager.windows().size(), 1u);
    const unsigned long field = manager.windows()[0]->winId();

    std::set<unsigned long> card_ids, ring_ids;
    std::vector<std::string> wrong;
    int events = 0;
    auto check = [&](const StackWatch& w, const std::string& what) {
        ++events;
        for (unsigned long card : card_ids) {
            if (!w.mapped(card)) continue;
            std::vector<unsigned long> under = {field};
            under.insert(under.end(), ring_ids.begin(), ring_ids.end());
            for (unsigned long below : under)
                if (w.mapped(below) && w.position(below) > w.position(card))
                    wrong.push_back("after event " + std::to_string(events) + " (" + what + "): window " +
                                    std::to_string(below) + " over the card");
        }
    };
    // Runs the event loop, replaying the server's events as they come.
    auto pump_for = [&](int ms) {
        QElapsedTimer clock;
        clock.start();
        while (clock.elapsed() < ms) {
            QCoreApplication::processEvents(QEventLoop::AllEvents, 2);
            for (PutCard* card : cards.cards()) card_ids.insert(card->winId());
            for (AimWindow* ring : manager.aim_windows()) ring_ids.insert(ring->winId());
            watch.drain(check);
            std::this_thread::sleep_for(std::chrono::milliseconds(2));
        }
    };
    pump_for(300);
    ASSERT_TRUE(manager.windows()[0]->isVisible());

    // A put at the screen's centre: its card beside the point, the ring on it.
    PutOffer offer;
    offer.id = 1;
    offer.client = "Pixel 7";
    offer.kind = umf::protocol::ContentKind::file;
    offer.name = "notes.txt";
    offer.mime = "text/plain";
    offer.size = 15;
    offer.at = ScreenPoint{0, 960, 540, 960, 540};
    cards.ask(offer, [](PutReply) {});
    const int screen = manager.screens()[0].index;
    manager.set_aim_mark(screen, QPointF(960, 540), "notes.txt");
    pump_for(300);
    ASSERT_EQ(cards.cards().size(), 1u);
    ASSERT_EQ(manager.aim_windows().size(), 1u);

    // Another program's window over everything: the field raises itself
    // over it (twice a second and a half), the ring kept up by aims.
    Plain other;
    other.setGeometry(400, 300, 1200, 600);
    other.show();
    const int restacks_before = watch.restacks(field);
    for (int i = 0; i < 5; ++i) {
        manager.set_aim_mark(screen, QPointF(960 + i, 540), "notes.txt");
        pump_for(500);
    }
    EXPECT_GE(watch.restacks(field) - restacks_before, 2) << "the field did not raise itself";
    // A snapshot: the field and the card unmapped and back, in the
    // provider's order.
    manager.hide_for_snapshot();
    cards.hide_for_snapshot();
    pump_for(200);
    manager.show_after_snapshot();
    cards.show_after_snapshot();
    manager.set_aim_mark(screen, QPointF(960, 540), "notes.txt");
    pump_for(1300);

    EXPECT_GT(events, 10);
    EXPECT_TRUE(wrong.empty()) << wrong.size() << " moments with the field over the card, the first: " << wrong[0];
    // At rest: card over ring over field over the other window.
    ASSERT_EQ(card_ids.size(), 1u);
    ASSERT_EQ(manager.aim_windows().size(), 1u);
    const unsigned long card = *card_ids.begin(), ring = manager.aim_windows()[0]->winId();
    const unsigned long frame = watch.top_level(other.winId());
    EXPECT_GT(watch.position(card), watch.position(ring));
    EXPECT_GT(watch.position(ring), watch.position(field));
    EXPECT_GT(watch.position(field), watch.position(frame)) << "the field stayed under a window mapped since";
}

TEST(OverlayStacking, ThePutCardStaysOverTheFieldInEveryRestack) {
    std::string log;
    run_x11_child("OverlayStackingOnX.DISABLED_Child", "1920x1080x24", {"xcompmgr"}, log);
}

}  // namespace

#endif
