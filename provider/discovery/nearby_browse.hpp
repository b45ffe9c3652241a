// Keeps a provider's NearbyScreens current: asks the Avahi daemon for the
// screens announced on the network (native/screen_discovery.hpp) at once and
// then every `period`, in a thread of its own, leaving this screen out by its
// fingerprint. Where libavahi-client was not built in or the daemon does not
// answer, the list stays empty and the reason is given once.
#pragma once

#include <chrono>
#include <condition_variable>
#include <functional>
#include <memory>
#include <mutex>
#include <string>
#include <thread>

#include "provider/discovery/nearby_screens.hpp"

namespace umf::provider {

class NearbyBrowse {
public:
    struct Settings {
        std::string own_fingerprint;
        std::chrono::milliseconds period{30000};
        double browse_timeout_s = 3.0;  // one browse's longest wait for the daemon's answers
        // Called from the browsing thread when the list changed, and once with
        // why not when browsing is not possible (list empty then).
        std::function<void(const std::vector<NearbyScreen>&, const std::string& why_not)> changed;
    };
    NearbyBrowse(Settings settings, std::shared_ptr<NearbyScreens> screens);
    // Waits for a browse under way (at most browse_timeout_s).
    ~NearbyBrowse();
    NearbyBrowse(const NearbyBrowse&) = delete;
    NearbyBrowse& operator=(const NearbyBrowse&) = delete;

private:
    void run();

    Settings settings_;
    std::shared_ptr<NearbyScreens> screens_;
    std::mutex mutex_;
    std::condition_variable wake_;
    bool stopping_ = false;
    std::thread thread_;  // last: started once the rest is in place
};

}  // namespace umf::provider
