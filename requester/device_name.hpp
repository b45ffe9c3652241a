// The name this requester gives in its hello's `device`, so that the person
// at a screen can say "always accept from this device". Random, made once
// and kept in $XDG_CONFIG_HOME/umf/requester-device: a name that others
// could guess would let them borrow the trust.
#pragma once

#include <filesystem>
#include <string>

namespace umf::requester {

// The kept name, or a new one kept from now on. When it cannot be kept
// (a read-only home), a new name for this run only, and `note` says why.
std::string device_name(const std::filesystem::path& file, std::string& note);

// $XDG_CONFIG_HOME/umf/requester-device (~/.config/... without it).
std::filesystem::path default_device_file();

// The hello's `client`, what a screen's prompt calls this requester:
// "umf-requester/VERSION on HOSTNAME" (the host name in printable ASCII, at
// most 64 bytes; left out when there is none).
std::string client_name();

}  // namespace umf::requester
