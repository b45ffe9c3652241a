// The desktop prompt for a put (put_decision.hpp): a small card near the
// place the phone points at, saying what comes from whom, with buttons
// Open / Save / Dismiss (a URL: Open / Dismiss), a toggle "Always accept from
// this device" when the requester named its device, and the time left until
// the card dismisses the put by itself. Like the aim ring
// (overlay/aim_window.hpp) it is an unmanaged window on top, painted by
// hand with Qt Gui; unlike the ring it takes clicks, but never the keyboard
// focus, so whatever the person is typing in keeps it. Several offers at
// once: one card each, stacked without overlapping.
#pragma once

#include <QObject>
#include <QPointF>
#include <QRasterWindow>
#include <QRect>
#include <QString>
#include <QStringList>
#include <QTimer>
#include <chrono>
#include <cstdint>
#include <functional>
#include <map>
#include <memory>
#include <optional>
#include <vector>

#include "provider/put/put_decision.hpp"

class QScreen;

namespace umf::provider {

class PutCard : public QRasterWindow {
public:
    using Clock = std::chrono::steady_clock;
    enum class Part { none, open, save, dismiss, always };

    // `on_answer` is called once, on the Qt thread, when a button is clicked
    // (not for the toggle); the card does not close itself: its owner does.
    PutCard(PutOffer offer, QScreen* screen, Clock::time_point deadline, std::function<void(PutReply)> on_answer);

    const PutOffer& offer() const { return offer_; }
    // What the card says above its buttons, line by line, as drawn (elided to
    // the card's width): "Incoming: report.pdf", "2.3 MB, from Pixel 7"; a
    // URL: "Incoming: Talk page", the URL, "from Pixel 7".
    const QStringList& lines() const { return lines_; }
    // "Dismissing in 27 s"; the seconds left, rounded up.
    QString countdown_text() const;
    int seconds_left() const;
    // Moves the countdown on (repainting when the text changed); whether the
    // deadline has passed.
    bool tick();

    bool always() const { return always_; }
    // Where each part is within the window, in logical pixels; an empty rect
    // for a part this card does not have (save for a URL, the toggle without
    // a device).
    QRect part_rect(Part part) const;
    Part part_at(QPointF position) const;
    // A click on `part` as the mouse gives it: a button answers (once), the
    // toggle toggles.
    void click(Part part);
    bool answered() const { return answered_; }

    // Draws the card as paintEvent does (tests render it to an image).
    void paint_to(QPainter& painter);

    static constexpr int kMaxWidth = 440;     // logical pixels
    static constexpr int kScreenMargin = 8;   // kept free at the screen's edges
    static constexpr double kTextPointSize = 10.0;

protected:
    void paintEvent(QPaintEvent* event) override;
    void mousePressEvent(QMouseEvent* event) override;
    void mouseReleaseEvent(QMouseEvent* event) override;
    void mouseMoveEvent(QMouseEvent* event) override;
    bool event(QEvent* event) override;  // the pointer leaving: no hover

private:
    void lay_out();
    QString button_text(Part part) const;

    PutOffer offer_;
    Clock::time_point start_, deadline_;
    std::function<void(PutReply)> on_answer_;
    QStringList lines_;
    std::vector<std::pair<Part, QRect>> parts_;
    QRect countdown_rect_;
    int shown_seconds_ = -1;
    bool always_ = false;
    bool answered_ = false;
    Part pressed_ = Part::none;
    Part hovered_ = Part::none;
};

// Where a card of `size` goes (all in the desktop's logical pixels): beside
// `at` (below and right of it, or on whichever side there is room, so the
// point itself stays visible), or centred on `screen` without one; inside
// `screen` less PutCard::kScreenMargin; clear of the `taken` cards when
// there is any such place on the screen, else stepped down and right from
// the first choice.
QRect place_put_card(QSize size, std::optional<QPointF> at, const QRect& screen, const std::vector<QRect>& taken);

// The prompt as a PutDecider: one card per offer. Made and destroyed on the
// Qt thread (the server must stop asking first); ask and withdraw may be
// called from any thread and hand over to the Qt thread. A card left
// unanswered past `answer_timeout` answers dismiss itself.
class PutPromptDecider : public PutDecider {
public:
    // The QScreen showing the welcome's screen `index`; nullptr: the
    // primary screen. The default takes QGuiApplication::screens()[index].
    using ScreenLookup = std::function<QScreen*(int index)>;

    explicit PutPromptDecider(std::chrono::seconds answer_timeout, ScreenLookup screens = {});
    ~PutPromptDecider() override;
    PutPromptDecider(const PutPromptDecider&) = delete;
    PutPromptDecider& operator=(const PutPromptDecider&) = delete;

    void ask(const PutOffer& offer, std::function<void(PutReply)> answer) override;
    void withdraw(std::uint64_t id) override;

    // Around a snapshot of a window or the screen, on the Qt thread, as
    // OverlayManager::hide_for_snapshot: a requester's snapshot must not
    // show another's put. The cards are unmapped (cards asked for meanwhile
    // wait unmapped) and come back when the last of nested calls ends; their
    // countdowns go on.
    void hide_for_snapshot();
    void show_after_snapshot();
    // On the Qt thread: the cards on the screen now (none around a
    // snapshot), lowest first: what the field stays under
    // (OverlayManager::set_windows_over_field).
    std::vector<QWindow*> shown_cards() const;

    // On the Qt thread: the cards up, oldest first; one by id (nullptr).
    std::vector<PutCard*> cards() const;
    PutCard* card(std::uint64_t id) const;

    static constexpr int kTickMs = 250;

private:
    struct Shown {
        PutCard* card = nullptr;  // deleted later: it may be in its own mouse event
        std::function<void(PutReply)> answer;
    };

    void show(const PutOffer& offer, std::function<void(PutReply)> answer);
    void map_card(PutCard* card);
    void finish(std::uint64_t id, std::optional<PutReply> reply);
    void tick();

    std::chrono::seconds timeout_;
    ScreenLookup screens_;
    std::unique_ptr<QObject> context_;  // what ask and withdraw post to
    QTimer* timer_ = nullptr;           // a child of context_
    std::map<std::uint64_t, Shown> shown_;
    int snapshot_depth_ = 0;
};

}  // namespace umf::provider
