// umf-requester discover's output: one screen of the network
// (native/screen_list.hpp) as a line for people or as a JSON object.
#pragma once

#include <string>

#include "native/screen_list.hpp"

namespace umf::requester {

// "umf on desk  https://desk.local:8443  10.0.0.5  fp HEX", "  (paired)" at
// the end when paired. Control characters an announcer put in a name are
// shown as '?' so that one screen is always one line.
std::string screen_line(const umf::native::AnnouncedScreen& screen);

// {"name":...,"host":...,"port":...,"addresses":[...],"fingerprint":...,
// "version":...}; "fingerprint" and "version" only when known, "paired" only
// when `with_paired` (discover --url, or screens kept with pair). Bytes that are not UTF-8 become U+FFFD.
std::string screen_json(const umf::native::AnnouncedScreen& screen, bool with_paired);

}  // namespace umf::requester
