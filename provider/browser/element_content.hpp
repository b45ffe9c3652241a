// What a grab takes from a browser window: the page's answer about the point
// (the extension's elementAtScreenPoint: a link, an image, a video, or the
// passage of text there) turned into the content sent to the phone. Pure.
#pragma once

#include <nlohmann/json_fwd.hpp>
#include <string>

#include "provider/browser/browser_windows.hpp"
#include "provider/content/resolver.hpp"

namespace umf::provider {

// `element` is the answer's "element" object, or null when the page did not
// answer; `tab` is the window's active tab as last reported (its URL http(s)).
// Always a kind url: a link's or an image's URL when it may leave the machine,
// a video's page with its time where the site takes one (t=), else the page
// with a text fragment (#:~:text=) naming the passage under the point.
Resolved content_of_element(const nlohmann::json& element, const BrowserTab& tab);

// A text fragment directive's value: every byte but letters, digits and
// ._~ percent-encoded (so '-', ',' and '&' never end a term early).
std::string text_fragment_term(const std::string& text);

// "12:31", "1:02:03".
std::string media_time(double seconds);

}  // namespace umf::provider
