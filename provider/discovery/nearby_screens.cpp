#include "provider/discovery/nearby_screens.hpp"

#include <algorithm>
#include <nlohmann/json.hpp>

#include "shared/protocol/pairing_url.hpp"

namespace umf::provider {

std::vector<NearbyScreen> nearby_from(const std::vector<native::AnnouncedScreen>& screens,
                                      const std::string& own_fingerprint) {
    std::vector<NearbyScreen> out;
    for (const auto& s : screens) {
        const bool other = !s.fingerprint.empty() && s.fingerprint != own_fingerprint;
        if (!other || s.port == 0 || !protocol::is_local_host_name(s.host)) continue;
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
