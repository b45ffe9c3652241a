// Setting up the browser companion: the native-messaging host manifests that
// let Chromium, Chrome, Edge and Firefox start umf-browser-host for the umf
// extension (and for it alone), in the per-user folders or, with `system`,
// in the system folders under a prefix.
#pragma once

#include <filesystem>
#include <string>
#include <vector>

namespace umf::provider {

// The host's name in every manifest, as the extension connects to it.
inline constexpr const char* kBrowserHostName = "org.umf.browser";
// Chromium's id of the extension, fixed by the public "key" in its
// manifest.json (a test recomputes it from there).
inline constexpr const char* kChromiumExtensionId = "dbjgngdppighniokcoaabhlpkkjkhajm";
// Firefox's id of the extension (manifest.json, browser_specific_settings).
inline constexpr const char* kFirefoxExtensionId = "browser-companion@umf.invalid";

struct HostManifest {
    std::string browser;            // "Chromium", "Google Chrome", "Microsoft Edge", "Firefox"
    std::filesystem::path file;     // where it goes
    std::string text;               // its JSON
};

struct HostManifestPlaces {
    std::filesystem::path home;         // per user: ~/.config/..., ~/.mozilla/...
    std::filesystem::path config_home;  // $XDG_CONFIG_HOME, else home/.config
    bool system = false;                // /etc/... and /usr/lib/mozilla/... instead
    std::filesystem::path prefix = "/"; // what the system folders are under
};

// The manifests for `host` (an absolute path to umf-browser-host). Throws
// std::invalid_argument when `host` is not absolute.
std::vector<HostManifest> host_manifests(const std::filesystem::path& host, const HostManifestPlaces& places);

// Chromium's extension id of a manifest's "key" (base64 of a DER public key):
// the first 128 bits of its SHA-256, each hex digit as a letter a..p.
std::string chromium_extension_id(const std::string& key_base64);

}  // namespace umf::provider
