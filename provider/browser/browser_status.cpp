#include "provider/browser/browser_status.hpp"

#include <sstream>

#include "provider/put/put_text.hpp"

namespace umf::provider {

using json = nlohmann::json;

json browser_status(const std::vector<BrowserState>& browsers) {
    json out = json::array();
    for (const BrowserState& b : browsers) {
        json windows = json::array();
        for (const BrowserWindow& w : b.windows)
            windows.push_back({{"id", w.id},
                               {"bounds", {w.bounds.x, w.bounds.y, w.bounds.width, w.bounds.height}},
                               {"focused", w.focused},
                               {"url", w.tab.url},
                               {"title", w.tab.title}});
        out.push_back({{"name", b.name}, {"version", b.version}, {"pid", b.pid}, {"windows", std::move(windows)}});
    }
    return out;
}

std::string browser_status_text(const json& browsers) {
    std::ostringstream out;
    if (!browsers.is_array() || browsers.empty()) {
        out << "no browser is connected; set the companion up with: umf-provider browser install\n";
        return out.str();
    }
    for (const json& b : browsers) {
        const auto windows = b.value("windows", json::array());
        out << printable_text(b.value("name", std::string("?"))) << " " << printable_text(b.value("version", std::string()))
            << " (pid " << b.value("pid", 0) << "): " << windows.size() << (windows.size() == 1 ? " window" : " windows")
            << "\n";
        for (const json& w : windows) {
            const std::string url = w.value("url", std::string());
            out << "  " << (w.value("focused", false) ? "* " : "  ") << printable_text(w.value("title", std::string()))
                << " — " << (url.empty() ? std::string("(not shared: not an http(s) page)") : printable_text(url)) << "\n";
        }
    }
    return out.str();
}

}  // namespace umf::provider
