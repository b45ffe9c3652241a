#include "provider/browser/browser_resolver.hpp"

#include <algorithm>
#include <cctype>
#include <stdexcept>

#include "provider/browser/base64.hpp"
#include "provider/browser/element_content.hpp"
#include "provider/content/file_facts.hpp"

namespace umf::provider {

namespace {

std::string lower(std::string s) {
    std::transform(s.begin(), s.end(), s.begin(), [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
    return s;
}

}  // namespace

bool is_browser_window(const WindowInfo& window) {
    static const char* const kBrowsers[] = {"chromium", "google-chrome", "chrome", "microsoft-edge",
                                            "firefox",  "firefox-esr",   "navigator", "brave-browser"};
    for (const std::string& name : {lower(window.wm_class), lower(window.instance)})
        for (const char* browser : kBrowsers)
            if (name == browser || name.rfind(std::string(browser) + "-", 0) == 0 ||
                name.rfind(std::string("org.mozilla.") + browser, 0) == 0)
                return true;
    return false;
}

BrowserResolver::BrowserResolver(std::shared_ptr<const Desktop> desktop, WindowFilter filter,
                                 std::shared_ptr<BrowserLink> link, std::ostream* hints, BrowserResolverOptions options)
    : desktop_(std::move(desktop)), filter_(std::move(filter)), link_(std::move(link)), hints_(hints), options_(options),
      memory_(options.aim_memory) {
    if (!desktop_ || !link_) throw std::invalid_argument("BrowserResolver: no desktop or no browser link");
}

std::optional<BrowserMatch> BrowserResolver::browser_window_at(const ScreenPoint& point,
                                                              const std::vector<BrowserState>& browsers,
                                                              std::optional<WindowInfo>* desktop_window) const {
    const auto window = desktop_->window_at(point.root_x, point.root_y, filter_);
    if (desktop_window) *desktop_window = window;
    if (!window || browsers.empty() || !match_browser_window(browsers, *window)) return std::nullopt;
    // Only a browser's window is worth listing the others for.
    return match_browser_window(browsers, *window, desktop_->windows());
}

std::optional<Resolved> BrowserResolver::image_file(const BrowserMatch& match, const Resolved& as_url) const {
    const auto answer = link_->ask(match.connection,
                                   {{"type", "image_bytes"},
                                    {"tab", match.window.tab.id},
                                    {"url", as_url.url},
                                    {"max_bytes", options_.max_image_bytes}},
                                   options_.image_timeout);
    if (!answer || !answer->contains("base64") || !(*answer)["base64"].is_string()) return std::nullopt;
    auto bytes = base64_decode((*answer)["base64"].get_ref<const std::string&>());
    if (!bytes || static_cast<std::int64_t>(bytes->size()) > options_.max_image_bytes) return std::nullopt;
    Resolved file;
    file.kind = protocol::ContentKind::file;
    file.title = as_url.title;
    file.name = protocol::safe_file_name(as_url.title.substr(std::string("Image: ").size()));
    const std::string mime = answer->value("mime", std::string());
    file.mime = mime.rfind("image/", 0) == 0 && mime.size() < 64 && mime.find_first_of("\r\n") == std::string::npos
                    ? mime.substr(0, mime.find(';'))
                    : mime_for(file.name);
    file.bytes = std::make_shared<const std::string>(std::move(*bytes));
    return file;
}

bool BrowserResolver::open_tab_at(const ScreenPoint& point, const std::string& url) const {
    if (!is_shareable_url(url)) return false;
    const auto match = browser_window_at(point, link_->browsers());
    if (!match) return false;
    const auto answer = link_->ask(match->connection, {{"type", "open_tab"}, {"window", match->window.id}, {"url", url}},
                                   options_.open_timeout);
    return answer && answer->value("opened", false);
}

std::optional<Resolved> BrowserResolver::resolve(const ScreenPoint& point, Purpose purpose) const {
    const auto browsers = link_->browsers();
    // Nothing to match and nothing to say: the window resolver looks the window up itself.
    if (browsers.empty() && (purpose != Purpose::grab || !hints_ || hinted_)) return std::nullopt;
    std::optional<WindowInfo> window;
    const auto match = browser_window_at(point, browsers, &window);
    if (!window) return std::nullopt;
    if (!match) {
        if (purpose == Purpose::grab && browsers.empty() && hints_ && is_browser_window(*window) && !hinted_.exchange(true))
            *hints_ << "browser: a grab on " << (window->wm_class.empty() ? "a browser" : window->wm_class)
                    << " gave a picture of it; with the browser companion it gives the page: umf-provider browser install\n"
                    << std::flush;
        return std::nullopt;
    }
    const BrowserTab& tab = match->window.tab;
    if (tab.url.empty()) return std::nullopt;  // a browser's own page, or not http(s)
    // A browser that cannot tell where its window is (Wayland) cannot turn a
    // screen point into a place in the page either: the page, never a wrong link.
    if (match->window.bounds.empty()) return content_of_element(nlohmann::json(), tab);
    // What lies at the point, from the page; the page itself when it does
    // not answer in time (an aim waits little: it only wants a title, and
    // takes the last answer where that still covers the point).
    const nlohmann::json question{{"type", "element_at"},
                                  {"window", match->window.id},
                                  {"tab", tab.id},
                                  {"screen_x", point.root_x},
                                  {"screen_y", point.root_y}};
    const auto answer = link_->ask(match->connection, question,
                                   purpose == Purpose::grab ? options_.grab_timeout : options_.aim_timeout);
    const auto element = answer ? answer->find("element") : nlohmann::json::const_iterator();
    nlohmann::json found = answer && element != answer->end() ? *element : nlohmann::json();
    if (answer) {
        memory_.remember(*match, found);
    } else if (purpose == Purpose::preview) {
        // Late: what the page said a moment ago of the element still under the point.
        if (auto kept = memory_.recall(*match, point.root_x, point.root_y)) found = std::move(*kept);
    }
    Resolved resolved = content_of_element(found, tab);
    if (purpose == Purpose::grab && found.is_object() && found.value("kind", "") == "image" &&
        resolved.title.rfind("Image: ", 0) == 0)
        if (auto file = image_file(*match, resolved)) return file;
    return resolved;
}

}  // namespace umf::provider
