// The screens this requester is paired with (`umf-requester pair URL`), kept
// in $XDG_CONFIG_HOME/umf/requester-screens.json (0600: the pairing URLs
// carry tokens). Grab and put without --url aim at the first; pointed at
// another screen, they look for its field among the others and switch to
// the one in view.
//   {"format": "umf-requester-screens/1",
//    "screens": [{"name": "desk-1", "url": "https://192.168.1.20:47470/#t=...&fp=..."}]}
#pragma once

#include <filesystem>
#include <string>
#include <vector>

#include "shared/protocol/pairing_url.hpp"

namespace umf::requester {

struct PairedScreen {
    std::string name;  // as the screen's welcome named it
    protocol::PairingUrl url;
    std::string url_text;  // the URL as given
};

// At most this many are kept: beyond them, the one used longest ago is dropped.
inline constexpr std::size_t kMaxPairedScreens = 32;

std::filesystem::path default_paired_screens_file();

// The kept screens, most recently paired or used first; none when the file
// does not exist. Throws InputError for a file that cannot be read or is not
// such a list (it is left as it is).
std::vector<PairedScreen> read_paired_screens(const std::filesystem::path& file);

// Writes them (0600). Throws InputError.
void write_paired_screens(const std::filesystem::path& file, const std::vector<PairedScreen>& screens);

// `screens` with `screen` first: a pairing of the same screen (the same
// root fingerprint) is replaced, whatever its address or token.
std::vector<PairedScreen> with_screen_first(std::vector<PairedScreen> screens, PairedScreen screen);

// `screens` without the one named `name_or_url` (a screen's name, or its
// pairing URL). Returns whether one was there.
bool forget_screen(std::vector<PairedScreen>& screens, const std::string& name_or_url);

}  // namespace umf::requester
