#include "discovery/nearby_screens.hpp"

#include <algorithm>
#include <cctype>
#include <nlohmann/json.hpp>

namespace umf::provider {

namespace {

// A DNS name under .local, letters, digits and hyphens, nothing a URL
// would read as anything but a host.
bool is_local_host(const std::string& host) {
    constexpr std::string_view kLocal = ".local";
    if (host.size() <= kLocal.size() || host.size() > 253 || !host.ends_with(kLocal)) return false;
    std::size_t label = 0;
    for (const char c : host) {
        if (c == '.') {
            if (label == 0) return false;
            label = 0;
        } else if (std::isalnum(static_cast<unsigned char>(c)) || c == '-') {
            if (++label > 63) return false;
        } else {
            return false;
        }
    }
    return true;
}

}  // namespace

std::vector<NearbyScreen> nearby_from(const std::vector<native::AnnouncedScreen>& screens,
                                      const std::string& own_fingerprint) {
    std::vector<NearbyScreen> out;
    for (const auto& s : screens) {
        const bool other = !s.fingerprint.empty() && s.fingerprint != own_fingerprint;
        if (!other || s.port == 0 || !is_local_host(s.host)) continue;
        out.push_back({s.name, "https://" + s.host + ":" + std::to_string(s.port), s.fingerprint});
    }
    std::sort(out.begin(), out.end(), [](const NearbyScreen& a, const NearbyScreen& b) { return a.name < b.name; });
    if (out.size() > kMaxNearbyScreens) out.resize(kMaxNearbyScreens);
    return out;
}

std::string nearby_json(const std::vector<NearbyScreen>& screens) {
    nlohmann::ordered_json list = nlohmann::ordered_json::array();
    for (const auto& s : screens)
        list.push_back({{"name", s.name}, {"origin", s.origin}, {"fingerprint", s.fingerprint}});
    const nlohmann::ordered_json body = {{"screens", list}};
    return body.dump(-1, ' ', false, nlohmann::ordered_json::error_handler_t::replace);
}

std::vector<NearbyScreen> NearbyScreens::list() const {
    std::lock_guard lock(mutex_);
    return screens_;
}

bool NearbyScreens::set(std::vector<NearbyScreen> screens) {
    std::lock_guard lock(mutex_);
    if (screens == screens_) return false;
    screens_ = std::move(screens);
    return true;
}

}  // namespace umf::provider
