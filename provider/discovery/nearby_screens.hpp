// The other screens announced on the local network, as the phone page needs
// them when it is pointed at a screen that is not its own: each one's name,
// the origin of its page and its root's fingerprint (docs/PROTOCOL.md,
// "Nearby screens"). nearby_browse.hpp keeps the list current.
#pragma once

#include <cstddef>
#include <mutex>
#include <string>
#include <vector>

#include "native/screen_list.hpp"

namespace umf::provider {

// More screens than this in one room are left out of the list, by name: the
// page tries each one's field on a frame, and a phone has its limits.
inline constexpr std::size_t kMaxNearbyScreens = 16;

struct NearbyScreen {
    std::string name;         // the announced instance, "umf on desk"
    std::string origin;       // "https://desk.local:8443", where its page is
    std::string fingerprint;  // its root's, from its announcement
    bool operator==(const NearbyScreen&) const = default;
};

// The screens of `screens` that a page could open, by name: announced with a
// fingerprint other than `own_fingerprint` and a host name under .local
// (an announcer's host of any other form never becomes a link). At most
// kMaxNearbyScreens.
std::vector<NearbyScreen> nearby_from(const std::vector<native::AnnouncedScreen>& screens,
                                      const std::string& own_fingerprint);

// {"screens":[{"name":...,"origin":...,"fingerprint":...},...]}; bytes of a
// name that are not UTF-8 become U+FFFD.
std::string nearby_json(const std::vector<NearbyScreen>& screens);

// The list as last browsed, read by the server's threads and replaced by
// the browsing one.
class NearbyScreens {
public:
    std::vector<NearbyScreen> list() const;
    // True when the list differs from the one before.
    bool set(std::vector<NearbyScreen> screens);

private:
    mutable std::mutex mutex_;
    std::vector<NearbyScreen> screens_;
};

}  // namespace umf::provider
