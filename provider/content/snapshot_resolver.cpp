#include "provider/content/snapshot_resolver.hpp"

#include <QBuffer>
#include <QByteArray>
#include <QImage>
#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "shared/protocol/messages.hpp"

namespace umf::provider {

namespace {

// Room for "-snapshot.png" within a file name, and short enough to read.
constexpr std::size_t kMaxTitleStemBytes = 100;

bool is_troublesome(unsigned char c) {
    static constexpr std::string_view kReplaced = "/\\:*?\"<>|";
    return c < 0x20 || c == 0x7f || kReplaced.find(static_cast<char>(c)) != std::string_view::npos;
}

// Cuts at most `max_bytes` without splitting a UTF-8 sequence.
std::string clip_utf8(std::string text, std::size_t max_bytes) {
    if (text.size() <= max_bytes) return text;
    std::size_t end = max_bytes;
    while (end > 0 && (static_cast<unsigned char>(text[end]) & 0xC0) == 0x80) --end;
    text.resize(end);
    return text;
}

std::string title_stem(std::string_view title) {
    std::string stem;
    for (const char c : title) {
        const bool space = c == ' ' || c == '\t' || c == '\n' || c == '\r';
        if (space && (stem.empty() || stem.back() == ' ')) continue;
        stem += space ? ' ' : is_troublesome(static_cast<unsigned char>(c)) ? '_' : c;
    }
    stem = clip_utf8(std::move(stem), kMaxTitleStemBytes);
    // Hidden files start with a dot; Windows drops trailing dots and spaces.
    while (!stem.empty() && (stem.back() == ' ' || stem.back() == '.')) stem.pop_back();
    const std::size_t first = stem.find_first_not_of(". ");
    return first == std::string::npos ? std::string() : stem.substr(first);
}

// [lo, hi) of length at most `side` around `centre`, within [begin, end).
std::pair<int, int> centred_span(int begin, int end, double centre, int side) {
    if (end - begin <= side) return {begin, end};
    const int start = std::clamp(static_cast<int>(std::floor(centre)) - side / 2, begin, end - side);
    return {start, start + side};
}

std::string window_label(const WindowInfo& window) {
    if (!window.title.empty()) return window.title;
    if (!window.wm_class.empty()) return window.wm_class;
    return "Window";
}

}  // namespace

std::string encode_png(const Capture& capture) {
    if (capture.width <= 0 || capture.height <= 0 ||
        capture.pixels.size() != static_cast<std::size_t>(capture.width) * static_cast<std::size_t>(capture.height))
        throw std::runtime_error("snapshot: no pixels to encode");
    const QImage image(reinterpret_cast<const uchar*>(capture.pixels.data()), capture.width, capture.height,
                       static_cast<qsizetype>(capture.width) * 4, QImage::Format_RGB32);
    QByteArray bytes;
    QBuffer buffer(&bytes);
    if (!buffer.open(QIODevice::WriteOnly) || !image.save(&buffer, "PNG"))
        throw std::runtime_error("snapshot: PNG encoding failed");
    return std::string(bytes.constData(), static_cast<std::size_t>(bytes.size()));
}

std::string snapshot_file_name(std::string_view title) {
    std::string stem = title_stem(title);
    if (stem.empty()) stem = "screen";
    return protocol::safe_file_name(stem + "-snapshot.png");
}

WindowRect snapshot_rect(const WindowRect& window, const WindowRect& screen, double root_x, double root_y,
                         int max_side) {
    const int x0 = std::max(window.x, screen.x), y0 = std::max(window.y, screen.y);
    const int x1 = std::min(window.x + window.width, screen.x + screen.width);
    const int y1 = std::min(window.y + window.height, screen.y + screen.height);
    if (x1 <= x0 || y1 <= y0) return {};
    const auto [left, right] = centred_span(x0, x1, root_x, max_side);
    const auto [top, bottom] = centred_span(y0, y1, root_y, max_side);
    return {left, top, right - left, bottom - top};
}

SnapshotResolver::SnapshotResolver(std::shared_ptr<const Desktop> desktop, WindowFilter filter,
                                         bool enabled)
    : desktop_(std::move(desktop)), filter_(std::move(filter)), enabled_(enabled) {
    if (enabled_ && !desktop_) throw std::invalid_argument("SnapshotResolver: no desktop");
}

void SnapshotResolver::set_around_capture(std::function<void()> before, std::function<void()> after) {
    before_capture_ = std::move(before);
    after_capture_ = std::move(after);
}

std::optional<Resolved> SnapshotResolver::resolve(const ScreenPoint& point, Purpose purpose) const {
    if (!enabled_) return std::nullopt;
    const auto window = desktop_->window_at(point.root_x, point.root_y, filter_);
    if (!window) return std::nullopt;
    Resolved resolved;
    resolved.kind = protocol::ContentKind::snapshot;
    resolved.title = window_label(*window) + " (snapshot)";
    resolved.name = snapshot_file_name(window->title);
    resolved.mime = "image/png";
    if (purpose == Purpose::preview) return resolved;
    const WindowRect rect = snapshot_rect(window->rect, desktop_->screen(), point.root_x, point.root_y);
    if (before_capture_) before_capture_();
    struct After {
        const std::function<void()>& after;
        ~After() {
            if (after) after();
        }
    } restore{after_capture_};
    const Capture capture = desktop_->capture(rect);
    if (capture.pixels.empty()) return std::nullopt;
    resolved.bytes = std::make_shared<const std::string>(encode_png(capture));
    return resolved;
}

}  // namespace umf::provider
