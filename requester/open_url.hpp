// Opening a grabbed link in the desktop's browser, through xdg-open and
// without a shell: the URL is one argument, whatever characters it holds.
#pragma once

#include <string>

namespace umf::requester {

// Runs `xdg-open URL` and waits a few seconds for it to hand over. True when
// it reported success (or is still busy starting a browser); a failure is
// logged to stderr. The caller makes sure the URL is http: or https:.
bool open_url(const std::string& url);

}  // namespace umf::requester
