#include "provider/browser/host_manifests.hpp"

#include <nlohmann/json.hpp>
#include <stdexcept>

#include "native/sha256.hpp"
#include "provider/browser/base64.hpp"

namespace umf::provider {

namespace fs = std::filesystem;

namespace {

std::string manifest_text(const fs::path& host, bool firefox) {
    nlohmann::json j{{"name", kBrowserHostName},
                     {"description", "umf browser companion: relays between the umf extension and umf-provider"},
                     {"path", host.string()},
                     {"type", "stdio"}};
    if (firefox)
        j["allowed_extensions"] = {kFirefoxExtensionId};
    else
        j["allowed_origins"] = {std::string("chrome-extension://") + kChromiumExtensionId + "/"};
    return j.dump(2) + "\n";
}

}  // namespace

std::vector<HostManifest> host_manifests(const fs::path& host, const HostManifestPlaces& places) {
    if (!host.is_absolute()) throw std::invalid_argument("the host's path must be absolute: " + host.string());
    const std::string file = std::string(kBrowserHostName) + ".json";
    struct Place {
        const char* browser;
        fs::path user;
        fs::path system;
        bool firefox;
    };
    const fs::path config = places.config_home.empty() ? places.home / ".config" : places.config_home;
    const std::vector<Place> list = {
        {"Chromium", config / "chromium/NativeMessagingHosts", "etc/chromium/native-messaging-hosts", false},
        {"Google Chrome", config / "google-chrome/NativeMessagingHosts", "etc/opt/chrome/native-messaging-hosts", false},
        {"Microsoft Edge", config / "microsoft-edge/NativeMessagingHosts", "etc/opt/edge/native-messaging-hosts", false},
        {"Firefox", places.home / ".mozilla/native-messaging-hosts", "usr/lib/mozilla/native-messaging-hosts", true},
    };
    std::vector<HostManifest> out;
    for (const Place& p : list)
        out.push_back({p.browser, (places.system ? places.prefix / p.system : p.user) / file, manifest_text(host, p.firefox)});
    return out;
}

std::string chromium_extension_id(const std::string& key_base64) {
    const auto decoded = base64_decode(key_base64);
    if (!decoded) throw std::invalid_argument("the key is not base64");
    const std::string& der = *decoded;
    native::Sha256 sha;
    sha.update(der.data(), der.size());
    const std::string hex = sha.hex();
    std::string id;
    for (std::size_t i = 0; i < 32; ++i) {
        const char c = hex[i];
        id += static_cast<char>('a' + (c <= '9' ? c - '0' : c - 'a' + 10));
    }
    return id;
}

}  // namespace umf::provider
