// What `umf-provider browser status` shows: the connected browsers and their
// windows, as the control socket's JSON and as lines for a person.
#pragma once

#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "provider/browser/browser_windows.hpp"

namespace umf::provider {

// [{"name":"chromium","version":"156.0","pid":4242,"windows":[{"id":1,
//   "bounds":[x,y,w,h],"focused":true,"url":"https://...","title":"..."}]}]
nlohmann::json browser_status(const std::vector<BrowserState>& browsers);

// "chromium 156.0 (pid 4242): 1 window\n  * Title — https://...\n", or a
// line saying none is connected and how to set the companion up. Every text
// from a browser goes through printable_text.
std::string browser_status_text(const nlohmann::json& browsers);

}  // namespace umf::provider
