#include "provider/put/put_prompt_window.hpp"

#include <QEvent>
#include <QFontMetrics>
#include <QGuiApplication>
#include <QMouseEvent>
#include <QPainter>
#include <QPainterPath>
#include <QScreen>
#include <QSurfaceFormat>
#include <algorithm>
#include <climits>
#include <cmath>

#include "provider/put/put_text.hpp"

namespace umf::provider {

namespace {

constexpr int kPad = 12;          // inside the card's edge
constexpr int kLineGap = 3;       // between text lines
constexpr int kSectionGap = 10;   // text, toggle, buttons
constexpr int kButtonGap = 8;
constexpr int kButtonMinWidth = 64;
constexpr int kBoxSide = 14;      // the toggle's box
constexpr int kPointOffset = 28;  // from the point to the card: the ring (radius 18) stays clear
constexpr int kStackGap = 6;      // between stacked cards
constexpr double kRadius = 8.0;

QFont body_font() {
    QFont font;
    font.setPointSizeF(PutCard::kTextPointSize);
    return font;
}

QFont headline_font() {
    QFont font = body_font();
    font.setBold(true);
    font.setPointSizeF(PutCard::kTextPointSize + 1);
    return font;
}

// Text from the requester, made safe to show: no control characters, no
// bidirectional overrides (a name could otherwise pretend to end in .pdf).
QString shown(const std::string& text) {
    QString s = QString::fromStdString(printable_text(text));
    return s.simplified();
}

// A rect's distance from the first choice, for picking the nearest free place.
long long distance(const QRect& a, const QRect& b) {
    return std::llabs(static_cast<long long>(a.x()) - b.x()) + std::llabs(static_cast<long long>(a.y()) - b.y());
}

bool clear_of(const QRect& r, const std::vector<QRect>& taken) {
    for (const QRect& t : taken)
        if (r.intersects(t.adjusted(-kStackGap + 1, -kStackGap + 1, kStackGap - 1, kStackGap - 1))) return false;
    return true;
}

}  // namespace

QRect place_put_card(QSize size, std::optional<QPointF> at, const QRect& screen, const std::vector<QRect>& taken) {
    const QRect area = screen.adjusted(PutCard::kScreenMargin, PutCard::kScreenMargin, -PutCard::kScreenMargin,
                                       -PutCard::kScreenMargin);
    const int w = std::min(size.width(), std::max(1, area.width()));
    const int h = std::min(size.height(), std::max(1, area.height()));
    const auto clamp_x = [&](int x) { return std::clamp(x, area.left(), std::max(area.left(), area.right() + 1 - w)); };
    const auto clamp_y = [&](int y) { return std::clamp(y, area.top(), std::max(area.top(), area.bottom() + 1 - h)); };
    QPoint first;
    if (at) {
        const int px = static_cast<int>(std::lround(at->x())), py = static_cast<int>(std::lround(at->y()));
        // Below right of the point; left of it or above it where the screen ends.
        int x = px + kPointOffset, y = py + kPointOffset;
        if (x + w > area.right() + 1 && px - kPointOffset - w >= area.left()) x = px - kPointOffset - w;
        if (y + h > area.bottom() + 1 && py - kPointOffset - h >= area.top()) y = py - kPointOffset - h;
        first = {clamp_x(x), clamp_y(y)};
    } else {
        first = {clamp_x(area.center().x() - w / 2), clamp_y(area.center().y() - h / 2)};
    }
    const QRect wanted(first, QSize(w, h));
    if (clear_of(wanted, taken)) return wanted;
    // Candidates: the first choice's row and column, and beside each card
    // already up; the nearest free one wins.
    std::vector<int> xs{first.x()}, ys{first.y()};
    for (const QRect& t : taken) {
        xs.push_back(clamp_x(t.right() + 1 + kStackGap));
        xs.push_back(clamp_x(t.left() - kStackGap - w));
        ys.push_back(clamp_y(t.bottom() + 1 + kStackGap));
        ys.push_back(clamp_y(t.top() - kStackGap - h));
    }
    std::optional<QRect> best;
    for (int x : xs)
        for (int y : ys) {
            const QRect r(QPoint(x, y), QSize(w, h));
            if (clear_of(r, taken) && (!best || distance(r, wanted) < distance(*best, wanted))) best = r;
        }
    if (best) return *best;
    // The screen is full: cascade, so at least each card's top shows.
    const int step = 24 * static_cast<int>(taken.size() % 8);
    return {QPoint(clamp_x(first.x() + step), clamp_y(first.y() + step)), QSize(w, h)};
}

PutCard::PutCard(PutOffer offer, QScreen* screen, Clock::time_point deadline, std::function<void(PutReply)> on_answer)
    : offer_(std::move(offer)), start_(Clock::now()), deadline_(deadline), on_answer_(std::move(on_answer)) {
    QSurfaceFormat format;
    format.setAlphaBufferSize(8);  // rounded corners
    setFormat(format);
    // As the aim ring (aim_window.cpp): unmanaged, on top, never
    // focused; but it takes clicks (no WindowTransparentForInput).
    setFlags(Qt::FramelessWindowHint | Qt::WindowStaysOnTopHint | Qt::WindowDoesNotAcceptFocus | Qt::Tool |
             Qt::X11BypassWindowManagerHint);
    setTitle("umf put");
    if (screen) setScreen(screen);
    shown_seconds_ = seconds_left();
    lay_out();
}

QString PutCard::button_text(Part part) const {
    switch (part) {
        case Part::open: return QStringLiteral("Open");
        case Part::save: return QStringLiteral("Save");
        case Part::dismiss: return QStringLiteral("Dismiss");
        default: return {};
    }
}

void PutCard::lay_out() {
    const QFontMetrics head(headline_font()), body(body_font());
    const bool url = offer_.kind == protocol::ContentKind::url;
    const QString headline = QStringLiteral("Incoming: ") + shown(put_offer_name(offer_));
    const QString from = offer_.client.empty() ? QString() : QStringLiteral("from ") + shown(offer_.client);
    QStringList natural{headline};
    if (url) {
        natural << shown(offer_.url);
        if (!from.isEmpty()) natural << from;
    } else {
        natural << QString::fromStdString(human_size(offer_.size)) + (from.isEmpty() ? QString() : ", " + from);
    }
    const QString toggle_text = QStringLiteral("Always accept from this device");
    const bool toggle = !offer_.device.empty();

    // The buttons' row: the countdown left, the buttons right.
    std::vector<Part> buttons = url ? std::vector<Part>{Part::open, Part::dismiss}
                                    : std::vector<Part>{Part::open, Part::save, Part::dismiss};
    const int button_h = body.height() + 10;
    int buttons_w = 0;
    std::vector<int> button_w;
    for (Part p : buttons) {
        button_w.push_back(std::max(kButtonMinWidth, body.horizontalAdvance(button_text(p)) + 24));
        buttons_w += button_w.back() + (buttons_w ? kButtonGap : 0);
    }
    const int countdown_w = body.horizontalAdvance(QStringLiteral("Dismissing in 888 s"));
    const int row_w = countdown_w + kButtonGap + buttons_w;

    int text_w = row_w;
    for (int i = 0; i < natural.size(); ++i)
        text_w = std::max(text_w, (i == 0 ? head : body).horizontalAdvance(natural[i]) + 1);
    if (toggle) text_w = std::max(text_w, kBoxSide + 8 + body.horizontalAdvance(toggle_text));
    int max_w = kMaxWidth;
    if (screen()) max_w = std::min(max_w, screen()->geometry().width() - 2 * kScreenMargin);
    const int width = std::max(std::min(text_w + 2 * kPad, max_w), std::min(row_w + 2 * kPad, std::max(max_w, 1)));
    const int inner = width - 2 * kPad;

    lines_.clear();
    int y = kPad;
    for (int i = 0; i < natural.size(); ++i) {
        const QFontMetrics& m = i == 0 ? head : body;
        // Names and URLs keep both ends (the extension, the path's end).
        const Qt::TextElideMode mode = i == 0 || (url && i == 1) ? Qt::ElideMiddle : Qt::ElideRight;
        lines_ << m.elidedText(natural[i], mode, inner);
        y += m.height() + (i + 1 < natural.size() ? kLineGap : 0);
    }
    parts_.clear();
    y += kSectionGap;
    if (toggle) {
        const int h = std::max(kBoxSide, body.height());
        parts_.emplace_back(Part::always,
                            QRect(kPad, y, std::min(inner, kBoxSide + 8 + body.horizontalAdvance(toggle_text)), h));
        y += h + kSectionGap;
    }
    int x = width - kPad - buttons_w;
    for (std::size_t i = 0; i < buttons.size(); ++i) {
        parts_.emplace_back(buttons[i], QRect(x, y, button_w[i], button_h));
        x += button_w[i] + kButtonGap;
    }
    countdown_rect_ = QRect(kPad, y, std::max(0, width - 2 * kPad - buttons_w - kButtonGap), button_h);
    y += button_h + kPad;
    resize(width, y);
}

QString PutCard::countdown_text() const { return QStringLiteral("Dismissing in %1 s").arg(seconds_left()); }

int PutCard::seconds_left() const {
    const auto left = std::chrono::duration_cast<std::chrono::milliseconds>(deadline_ - Clock::now()).count();
    return left <= 0 ? 0 : static_cast<int>((left + 999) / 1000);
}

bool PutCard::tick() {
    const int s = seconds_left();
    // The bar along the bottom moves smoothly; the text once a second.
    update(QRect(0, height() - 6, width(), 6));
    if (s != shown_seconds_) {
        shown_seconds_ = s;
        update(countdown_rect_);
    }
    return Clock::now() >= deadline_;
}

QRect PutCard::part_rect(Part part) const {
    for (const auto& [p, r] : parts_)
        if (p == part) return r;
    return {};
}

PutCard::Part PutCard::part_at(QPointF position) const {
    for (const auto& [p, r] : parts_)
        if (QRectF(r).contains(position)) return p;
    return Part::none;
}

void PutCard::click(Part part) {
    if (answered_ || part == Part::none) return;
    if (part == Part::always) {
        always_ = !always_;
        update(part_rect(Part::always));
        return;
    }
    answered_ = true;
    const PutAnswer answer = part == Part::open ? PutAnswer::open : part == Part::save ? PutAnswer::save : PutAnswer::dismiss;
    if (on_answer_) on_answer_(PutReply{answer, always_ && answer != PutAnswer::dismiss});
}

void PutCard::paint_to(QPainter& painter) {
    painter.setCompositionMode(QPainter::CompositionMode_Source);
    painter.fillRect(QRect(QPoint(), size()), Qt::transparent);
    painter.setCompositionMode(QPainter::CompositionMode_SourceOver);
    painter.setRenderHint(QPainter::Antialiasing);
    const QRectF card = QRectF(QPointF(), QSizeF(size())).adjusted(0.5, 0.5, -0.5, -0.5);
    painter.setPen(QPen(QColor(255, 255, 255, 70), 1.0));
    painter.setBrush(QColor(30, 32, 36, 245));
    painter.drawRoundedRect(card, kRadius, kRadius);

    // The time left as a bar along the bottom edge, in whole ticks: the bar
    // is repainted once a tick, and a paint in between (a hover) draws the
    // same bar rather than one a few pixels off.
    const double tick = PutPromptDecider::kTickMs / 1000.0;
    const double total = std::chrono::duration<double>(deadline_ - start_).count();
    const double left = std::ceil(std::chrono::duration<double>(deadline_ - Clock::now()).count() / tick) * tick;
    const double fraction = total > 0 ? std::clamp(left / total, 0.0, 1.0) : 0.0;
    painter.save();
    QPainterPath clip;
    clip.addRoundedRect(card, kRadius, kRadius);
    painter.setClipPath(clip);
    painter.fillRect(QRectF(0, height() - 3, width() * fraction, 3), QColor(90, 160, 255));
    painter.restore();

    const QFont head = headline_font(), body = body_font();
    const QFontMetrics hm(head), bm(body);
    int y = kPad;
    for (int i = 0; i < lines_.size(); ++i) {
        const QFontMetrics& m = i == 0 ? hm : bm;
        painter.setFont(i == 0 ? head : body);
        painter.setPen(i == 0 ? QColor(255, 255, 255) : QColor(205, 210, 218));
        painter.drawText(QPoint(kPad, y + m.ascent()), lines_[i]);
        y += m.height() + kLineGap;
    }
    painter.setFont(body);
    if (const QRect r = part_rect(Part::always); !r.isEmpty()) {
        const QRectF box(r.x() + 0.5, r.y() + (r.height() - kBoxSide) / 2.0 + 0.5, kBoxSide - 1, kBoxSide - 1);
        painter.setPen(QPen(hovered_ == Part::always ? QColor(255, 255, 255) : QColor(170, 176, 186), 1.2));
        painter.setBrush(always_ ? QColor(90, 160, 255) : QColor(0, 0, 0, 0));
        painter.drawRoundedRect(box, 3, 3);
        if (always_) {
            QPainterPath tick;
            tick.moveTo(box.left() + 3, box.center().y());
            tick.lineTo(box.left() + 6, box.bottom() - 3);
            tick.lineTo(box.right() - 3, box.top() + 3);
            painter.setPen(QPen(Qt::white, 2.0, Qt::SolidLine, Qt::RoundCap, Qt::RoundJoin));
            painter.setBrush(Qt::NoBrush);
            painter.drawPath(tick);
        }
        painter.setPen(QColor(225, 228, 233));
        painter.drawText(QRect(r.x() + kBoxSide + 8, r.y(), r.width() - kBoxSide - 8, r.height()),
                         Qt::AlignVCenter | Qt::AlignLeft, QStringLiteral("Always accept from this device"));
    }
    painter.setPen(QColor(170, 176, 186));
    painter.drawText(countdown_rect_, Qt::AlignVCenter | Qt::AlignLeft, countdown_text());
    // The primary button: Save for a file, Open for a URL.
    const Part primary = offer_.kind == protocol::ContentKind::url ? Part::open : Part::save;
    for (const auto& [part, r] : parts_) {
        if (part == Part::always) continue;
        QColor fill = part == primary ? QColor(60, 125, 230) : QColor(62, 66, 74);
        if (part == hovered_) fill = fill.lighter(120);
        if (part == pressed_ && part == hovered_) fill = fill.darker(115);
        painter.setPen(Qt::NoPen);
        painter.setBrush(fill);
        painter.drawRoundedRect(QRectF(r), 5, 5);
        painter.setPen(Qt::white);
        painter.drawText(r, Qt::AlignCenter, button_text(part));
    }
}

void PutCard::paintEvent(QPaintEvent*) {
    QPainter painter(this);
    paint_to(painter);
}

void PutCard::mousePressEvent(QMouseEvent* event) {
    if (event->button() != Qt::LeftButton) return;
    pressed_ = part_at(event->position());
    update();
}

void PutCard::mouseReleaseEvent(QMouseEvent* event) {
    if (event->button() != Qt::LeftButton) return;
    const Part part = part_at(event->position());
    const Part pressed = pressed_;
    pressed_ = Part::none;
    update();
    // A button acts when the press and the release are both on it.
    if (part == pressed) click(part);
}

void PutCard::mouseMoveEvent(QMouseEvent* event) {
    const Part part = part_at(event->position());
    if (part != hovered_) {
        hovered_ = part;
        setCursor(part == Part::none ? Qt::ArrowCursor : Qt::PointingHandCursor);
        update();
    }
}

bool PutCard::event(QEvent* event) {
    if (event->type() == QEvent::Leave && hovered_ != Part::none) {
        hovered_ = Part::none;
        update();
    }
    return QRasterWindow::event(event);
}

PutPromptDecider::PutPromptDecider(std::chrono::seconds answer_timeout, ScreenLookup screens)
    : timeout_(answer_timeout), screens_(std::move(screens)), context_(std::make_unique<QObject>()) {
    timer_ = new QTimer(context_.get());
    timer_->setInterval(kTickMs);
    QObject::connect(timer_, &QTimer::timeout, context_.get(), [this] { tick(); });
}

PutPromptDecider::~PutPromptDecider() {
    // Queued asks and withdrawals go with the context.
    context_.reset();
    for (auto& [id, s] : shown_) delete s.card;
}

void PutPromptDecider::ask(const PutOffer& offer, std::function<void(PutReply)> answer) {
    QMetaObject::invokeMethod(
        context_.get(), [this, offer, answer = std::move(answer)]() mutable { show(offer, std::move(answer)); },
        Qt::QueuedConnection);
}

void PutPromptDecider::withdraw(std::uint64_t id) {
    QMetaObject::invokeMethod(context_.get(), [this, id] { finish(id, std::nullopt); }, Qt::QueuedConnection);
}

std::vector<PutCard*> PutPromptDecider::cards() const {
    std::vector<PutCard*> out;
    for (const auto& [id, s] : shown_) out.push_back(s.card);
    return out;
}

PutCard* PutPromptDecider::card(std::uint64_t id) const {
    const auto it = shown_.find(id);
    return it == shown_.end() ? nullptr : it->second.card;
}

void PutPromptDecider::show(const PutOffer& offer, std::function<void(PutReply)> answer) {
    if (shown_.count(offer.id)) return;  // asked twice: the first card stands
    QScreen* screen = nullptr;
    if (offer.at) {
        if (screens_) {
            screen = screens_(offer.at->screen);
        } else {
            const auto all = QGuiApplication::screens();
            if (offer.at->screen >= 0 && offer.at->screen < all.size()) screen = all[offer.at->screen];
        }
    }
    if (!screen) screen = QGuiApplication::primaryScreen();
    const std::uint64_t id = offer.id;
    auto* card = new PutCard(offer, screen, PutCard::Clock::now() + timeout_,
                             [this, id](PutReply reply) { finish(id, reply); });
    // The point in the desktop's logical pixels: the offer's are the
    // screen's physical ones (as the placement's).
    std::optional<QPointF> at;
    QRect screen_rect(0, 0, 800, 600);
    if (screen) {
        screen_rect = screen->geometry();
        if (offer.at) at = QPointF(screen_rect.topLeft()) + QPointF(offer.at->x, offer.at->y) / screen->devicePixelRatio();
    }
    std::vector<QRect> taken;
    for (const auto& [other, s] : shown_)
        if (s.card->screen() == card->screen()) taken.push_back(s.card->geometry());
    card->setGeometry(place_put_card(card->size(), at, screen_rect, taken));
    shown_[id] = Shown{card, std::move(answer)};
    if (snapshot_depth_ == 0) map_card(card);
    if (!timer_->isActive()) timer_->start();
}

void PutPromptDecider::map_card(PutCard* card) {
    // Above windows mapped before it, the field among them, and raised
    // before it is mapped: mapped first where it was (under the field,
    // after a snapshot), it would show under the field for a moment. The
    // offscreen platform cannot raise.
    if (QGuiApplication::platformName() != QLatin1String("offscreen")) {
        card->create();
        card->raise();
    }
    card->show();
}

void PutPromptDecider::hide_for_snapshot() {
    if (snapshot_depth_++ > 0) return;
    for (auto& [id, s] : shown_) s.card->hide();
}

void PutPromptDecider::show_after_snapshot() {
    if (snapshot_depth_ == 0 || --snapshot_depth_ > 0) return;
    for (auto& [id, s] : shown_) map_card(s.card);
}

std::vector<QWindow*> PutPromptDecider::shown_cards() const {
    // Each card is raised when mapped, and the map keeps their ids' order.
    std::vector<QWindow*> out;
    if (snapshot_depth_ > 0) return out;
    for (const auto& [id, s] : shown_)
        if (s.card->isVisible()) out.push_back(s.card);
    return out;
}

void PutPromptDecider::finish(std::uint64_t id, std::optional<PutReply> reply) {
    const auto it = shown_.find(id);
    if (it == shown_.end()) return;
    Shown s = std::move(it->second);
    shown_.erase(it);
    s.card->hide();
    s.card->deleteLater();
    if (shown_.empty()) timer_->stop();
    if (reply && s.answer) s.answer(*reply);
}

void PutPromptDecider::tick() {
    std::vector<std::uint64_t> expired;
    for (const auto& [id, s] : shown_)
        if (s.card->tick()) expired.push_back(id);
    // Past its time the card dismisses the put itself (the service, which
    // times out too, takes whichever comes first).
    for (std::uint64_t id : expired) finish(id, PutReply{PutAnswer::dismiss, false});
}

}  // namespace umf::provider
