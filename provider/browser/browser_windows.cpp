#include "provider/browser/browser_windows.hpp"

#include <algorithm>
#include <cmath>
#include <nlohmann/json.hpp>
#include <stdexcept>

#include "provider/common/json_fields.hpp"
#include "provider/put/put_text.hpp"
#include "shared/protocol/json_checks.hpp"
#include "shared/protocol/messages.hpp"

namespace umf::provider {

namespace {

using json = nlohmann::json;

constexpr std::size_t kMaxWindows = 256;
// Bounds a desktop reports include its frame; the browser's may not.
constexpr double kMinOverlap = 0.8;
constexpr std::size_t kLongTitleBytes = 64;

int int_of(const json& object, const char* key) {
    const auto it = object.find(key);
    if (it == object.end() || !it->is_number()) return 0;
    const double v = it->get<double>();
    if (!std::isfinite(v) || std::abs(v) > 1e6) throw std::invalid_argument(std::string("\"") + key + "\" is out of range");
    return static_cast<int>(std::lround(v));
}

bool is_private(const json& object) {
    const auto it = object.find("incognito");
    return it != object.end() && (!it->is_boolean() || it->get<bool>());
}

BrowserTab tab_of(const json& j) {
    if (!j.is_object()) throw std::invalid_argument("a window's \"tab\" must be an object");
    BrowserTab tab;
    if (j.contains("id") && j["id"].is_number_integer()) tab.id = j["id"].get<long>();
    const std::string url = json_text(j, "url");
    if (is_shareable_url(url)) tab.url = url;
    tab.title = browser_text(json_text(j, "title"));
    if (j.contains("zoom") && j["zoom"].is_number()) {
        const double zoom = j["zoom"].get<double>();
        if (std::isfinite(zoom) && zoom > 0.05 && zoom < 20) tab.zoom = zoom;
    }
    return tab;
}

long long overlap_area(const WindowRect& a, const WindowRect& b) {
    const long long w = std::min(a.x + a.width, b.x + b.width) - std::max(a.x, b.x);
    const long long h = std::min(a.y + a.height, b.y + b.height) - std::max(a.y, b.y);
    return w > 0 && h > 0 ? w * h : 0;
}

double overlap(const WindowRect& a, const WindowRect& b) {
    const long long both = overlap_area(a, b);
    const long long either = static_cast<long long>(a.width) * a.height + static_cast<long long>(b.width) * b.height - both;
    return either > 0 ? static_cast<double>(both) / static_cast<double>(either) : 0.0;
}

// The desktop's title begins with the tab's ("Page - Chromium"), or, for a
// long one that browsers cut short their own way ("Page of 300 charact… —
// Mozilla Firefox"), with its first 64 bytes.
bool titles_agree(const BrowserWindow& w, const WindowInfo& window) {
    const std::string& tab = w.tab.title;
    if (tab.empty() || window.title.empty()) return true;
    const std::size_t n = std::min(tab.size(), window.title.size());
    const std::size_t same = static_cast<std::size_t>(
        std::mismatch(tab.begin(), tab.begin() + static_cast<std::ptrdiff_t>(n), window.title.begin()).first - tab.begin());
    return same >= std::min<std::size_t>(tab.size(), kLongTitleBytes);
}

// Whether a desktop window could be the reported one.
bool could_be(const BrowserWindow& w, const WindowInfo& window) {
    if (!titles_agree(w, window)) return false;
    if (w.bounds.empty() || window.rect.empty()) return !w.tab.title.empty() && !window.title.empty();
    return overlap(w.bounds, window.rect) >= kMinOverlap;
}

}  // namespace

std::string browser_text(const std::string& raw) {
    return printable_text(protocol::clip_text(raw, protocol::kMaxTitleBytes));
}

bool is_shareable_url(const std::string& url) {
    if (url.empty() || url.size() > protocol::kMaxUrlBytes) return false;
    std::string scheme;
    for (char c : url) {
        if (c == ':') break;
        scheme += static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
    }
    if (scheme != "http" && scheme != "https") return false;
    if (url.compare(scheme.size(), 3, "://") != 0 || url.size() == scheme.size() + 3) return false;
    return std::none_of(url.begin(), url.end(), [](char c) {
        const auto u = static_cast<unsigned char>(c);
        return u <= 0x20 || u == 0x7f;
    });
}

std::vector<BrowserWindow> parse_browser_windows(const json& message) {
    if (!message.is_object() || !message.contains("windows") || !message["windows"].is_array())
        throw std::invalid_argument("a \"windows\" message holds an array \"windows\"");
    const json& list = message["windows"];
    if (list.size() > kMaxWindows) throw std::invalid_argument("too many windows");
    std::vector<BrowserWindow> windows;
    for (const json& j : list) {
        if (!j.is_object()) throw std::invalid_argument("a window must be an object");
        if (is_private(j)) continue;
        const auto tab = j.find("tab");
        if (tab != j.end() && tab->is_object() && is_private(*tab)) continue;
        BrowserWindow w;
        if (!j.contains("id") || !j["id"].is_number_integer()) throw std::invalid_argument("a window needs an integer \"id\"");
        w.id = j["id"].get<long>();
        w.bounds = {int_of(j, "left"), int_of(j, "top"), int_of(j, "width"), int_of(j, "height")};
        w.focused = j.contains("focused") && j["focused"].is_boolean() && j["focused"].get<bool>();
        if (tab != j.end() && !tab->is_null()) w.tab = tab_of(*tab);
        windows.push_back(std::move(w));
    }
    return windows;
}

std::optional<BrowserMatch> match_browser_window(const std::vector<BrowserState>& browsers, const WindowInfo& window,
                                                 const std::vector<WindowInfo>& others) {
    const BrowserWindow* best = nullptr;
    int best_connection = 0;
    double best_overlap = 0;
    int title_matches = 0;
    for (const BrowserState& browser : browsers) {
        if (window.pid != 0 && browser.pid != 0 && browser.pid != window.pid) continue;
        for (const BrowserWindow& w : browser.windows) {
            const bool titled = !w.tab.title.empty() && !window.title.empty();
            const bool same_title = titled && titles_agree(w, window);
            if (titled && !same_title) continue;
            if (w.bounds.empty() || window.rect.empty()) {
                // Only the title can tell (Wayland): it must, and alone.
                if (!same_title) continue;
                ++title_matches;
                best = &w;
                best_connection = browser.connection;
                best_overlap = 1;
                continue;
            }
            const double o = overlap(w.bounds, window.rect);
            if (o < kMinOverlap) continue;
            if (!best || o > best_overlap || (o == best_overlap && w.focused)) {
                best = &w;
                best_connection = browser.connection;
                best_overlap = o;
            }
        }
    }
    if (!best || title_matches > 1) return std::nullopt;
    for (const WindowInfo& other : others)
        if (other.id != window.id && (window.pid == 0 || other.pid == window.pid) && could_be(*best, other))
            return std::nullopt;
    return BrowserMatch{best_connection, *best};
}

}  // namespace umf::provider
