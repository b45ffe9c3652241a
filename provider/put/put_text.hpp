// How a put offer reads to the person at the screen, shared by the prompt
// (put_prompt_window.hpp) and `umf-provider puts`: the size in the units a
// file manager uses, a URL's host, one line saying what comes from whom.
// Everything here comes from the requester, so text meant for a terminal
// goes through printable_text first.
#pragma once

#include <cstdint>
#include <string>

#include "provider/put/put_decision.hpp"

namespace umf::provider {

// 512 -> "512 bytes", 48213 -> "47 KB", 2411724 -> "2.3 MB" (powers of 1024,
// one decimal below 10).
std::string human_size(std::int64_t bytes);

// "https://user@Example.org:8443/a?b" -> "Example.org"; "[::1]" for IPv6;
// the whole text when it is not scheme://host...
std::string put_url_host(const std::string& url);

// What the offer is called: a file's name; a URL's title, else its host.
std::string put_offer_name(const PutOffer& offer);

// "Incoming: report.pdf, 2.3 MB, from Pixel 7"; a URL: "Incoming: Talk page
// (https://example.org/talk), from Pixel 7". No "from" without a client.
std::string put_offer_summary(const PutOffer& offer);

// `text` with control characters (C0, DEL, C1) and the Unicode
// bidirectional overrides and isolates replaced by '?', so a name cannot
// move the terminal's cursor or pretend to end in another extension.
std::string printable_text(const std::string& text);

}  // namespace umf::provider
