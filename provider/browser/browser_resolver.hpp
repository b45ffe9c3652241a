// Resolver 3a (docs/ARCHITECTURE.md, "Content"): a browser window under the
// point gives its active tab's page, as a URL, when the browser companion
// (browser/) is connected; otherwise the window and snapshot resolvers
// answer as before, and the first time a browser window is pointed at the
// console says how to install the companion.
#pragma once

#include <atomic>
#include <chrono>
#include <cstdint>
#include <memory>
#include <ostream>

#include "provider/browser/browser_link.hpp"
#include "provider/browser/element_memory.hpp"
#include "provider/content/resolver.hpp"
#include "provider/desktop/desktop.hpp"

namespace umf::provider {

// Whether a desktop window's class or app id is a web browser's.
bool is_browser_window(const WindowInfo& window);

struct BrowserResolverOptions {
    // How long the page may take to say what is at the point.
    std::chrono::milliseconds grab_timeout{1000};
    std::chrono::milliseconds aim_timeout{40};
    // How long an aim that the page answers late may be given the element
    // the page last said covers the point (element_memory.hpp).
    std::chrono::milliseconds aim_memory{3000};
    std::chrono::milliseconds open_timeout{3000};
    // An image's bytes, fetched by the browser with the page's cookies; a
    // larger one, or one not fetched in time, is given as its URL.
    std::chrono::milliseconds image_timeout{10'000};
    std::int64_t max_image_bytes = 32 * 1024 * 1024;
};

class BrowserResolver final : public Resolver {
public:
    // `hints` (may be null) hears the one-time install hint.
    BrowserResolver(std::shared_ptr<const Desktop> desktop, WindowFilter filter, std::shared_ptr<BrowserLink> link,
                    std::ostream* hints = nullptr, BrowserResolverOptions options = {});
    const char* name() const override { return "browser"; }
    std::optional<Resolved> resolve(const ScreenPoint& point, Purpose purpose) const override;
    // Opens `url` (http or https) as a new tab in the browser window at the
    // point; false when no reported window is there or the browser did not.
    bool open_tab_at(const ScreenPoint& point, const std::string& url) const;

private:
    // The image `as_url` names, as a file of its bytes; nullopt when the
    // browser cannot give them.
    std::optional<Resolved> image_file(const BrowserMatch& match, const Resolved& as_url) const;
    std::optional<BrowserMatch> browser_window_at(const ScreenPoint& point, const std::vector<BrowserState>& browsers,
                                                  std::optional<WindowInfo>* desktop_window = nullptr) const;

    std::shared_ptr<const Desktop> desktop_;
    WindowFilter filter_;
    std::shared_ptr<BrowserLink> link_;
    std::ostream* hints_;
    BrowserResolverOptions options_;
    mutable std::atomic<bool> hinted_{false};
    mutable ElementMemory memory_;
};

}  // namespace umf::provider
