#include "provider/browser/element_content.hpp"

#include <cmath>
#include <cstdio>
#include <nlohmann/json.hpp>

#include "provider/common/json_fields.hpp"
#include "provider/put/put_text.hpp"
#include "shared/protocol/json_checks.hpp"

namespace umf::provider {

namespace {

using json = nlohmann::json;
constexpr std::size_t kMaxTermBytes = 200;

std::string without_fragment(const std::string& url) { return url.substr(0, url.find('#')); }

// The last path segment of a URL, for an image's title.
std::string file_name_of(const std::string& url) {
    std::string path = url.substr(0, url.find_first_of("?#"));
    const auto slash = path.find_last_of('/');
    return slash == std::string::npos ? path : path.substr(slash + 1);
}

std::string host_of(const std::string& url) {
    const auto start = url.find("://");
    if (start == std::string::npos) return {};
    const auto end = url.find_first_of("/?#", start + 3);
    std::string host = url.substr(start + 3, end == std::string::npos ? std::string::npos : end - start - 3);
    const auto at = host.find('@');
    if (at != std::string::npos) host = host.substr(at + 1);
    const auto colon = host.find(':');
    return host.substr(0, colon);
}

bool host_is(const std::string& host, const std::string& domain) {
    return host == domain || (host.size() > domain.size() && host.compare(host.size() - domain.size(), domain.size(), domain) == 0 &&
                              host[host.size() - domain.size() - 1] == '.');
}

// The page at `seconds`, where the site is known to take a time in its URL.
std::string page_at_time(const std::string& page, double seconds) {
    const std::string host = host_of(page);
    const std::string t = std::to_string(static_cast<long long>(std::floor(seconds))) + "s";
    if (host_is(host, "youtube.com") || host_is(host, "youtu.be")) {
        std::string base = without_fragment(page);
        // Drop any t= already there, then add ours.
        const auto q = base.find('?');
        std::string query = q == std::string::npos ? "" : base.substr(q + 1);
        base = base.substr(0, q);
        std::string kept;
        std::size_t i = 0;
        while (i <= query.size() && !query.empty()) {
            const auto amp = query.find('&', i);
            const std::string part = query.substr(i, amp == std::string::npos ? std::string::npos : amp - i);
            if (!part.empty() && part.rfind("t=", 0) != 0) kept += (kept.empty() ? "" : "&") + part;
            if (amp == std::string::npos) break;
            i = amp + 1;
        }
        return base + "?" + (kept.empty() ? "" : kept + "&") + "t=" + t;
    }
    if (host_is(host, "vimeo.com")) return without_fragment(page) + "#t=" + t;
    return page;
}

}  // namespace

std::string text_fragment_term(const std::string& text) {
    const std::string clipped = protocol::clip_text(text, kMaxTermBytes);
    std::string out;
    for (unsigned char c : clipped) {
        if (std::isalnum(c) || c == '.' || c == '_' || c == '~') {
            out += static_cast<char>(c);
        } else {
            char buf[4];
            std::snprintf(buf, sizeof buf, "%%%02X", c);
            out += buf;
        }
    }
    return out;
}

std::string media_time(double seconds) {
    const long long s = std::isfinite(seconds) && seconds > 0 ? static_cast<long long>(seconds) : 0;
    char buf[32];
    if (s >= 3600)
        std::snprintf(buf, sizeof buf, "%lld:%02lld:%02lld", s / 3600, (s / 60) % 60, s % 60);
    else
        std::snprintf(buf, sizeof buf, "%lld:%02lld", s / 60, s % 60);
    return buf;
}

Resolved content_of_element(const json& element, const BrowserTab& tab) {
    Resolved r;
    r.kind = protocol::ContentKind::url;
    const std::string answered_page = json_text(element, "page");
    const std::string page = is_shareable_url(answered_page) ? answered_page : tab.url;
    const std::string page_title = browser_text(json_text(element, "title").empty() ? tab.title : json_text(element, "title"));
    const std::string kind = json_text(element, "kind");
    const std::string url = json_text(element, "url");
    const std::string text = json_text(element, "text");
    if (kind == "link" && is_shareable_url(url)) {
        r.url = url;
        r.title = "Link: " + browser_text(text.empty() ? url : text);
        return r;
    }
    if (kind == "image" && is_shareable_url(url)) {
        r.url = url;
        const std::string name = file_name_of(url);
        r.title = "Image: " + browser_text(name.empty() ? (text.empty() ? url : text) : name);
        return r;
    }
    if (kind == "video" || kind == "audio") {
        double seconds = 0;
        if (element.contains("time") && element["time"].is_number()) seconds = element["time"].get<double>();
        const std::string at = page_at_time(page, seconds);
        r.url = at != page || !is_shareable_url(url) ? at : url;
        r.title = std::string(kind == "video" ? "Video" : "Audio") + " at " + media_time(seconds);
        return r;
    }
    r.url = page;
    const std::string start = json_text(element, "start");
    if (kind == "text" && !start.empty()) {
        // After the page's own fragment, if any (a route in a web app), as
        // the text fragment syntax allows.
        std::string url = page + (page.find('#') == std::string::npos ? "#" : "") + ":~:text=" + text_fragment_term(start);
        const std::string end = json_text(element, "end");
        if (!end.empty()) url += "," + text_fragment_term(end);
        if (url.size() <= protocol::kMaxUrlBytes) r.url = url;
    }
    r.title = "Page: " + (page_title.empty() ? page : page_title);
    return r;
}

}  // namespace umf::provider
