#include "provider/discovery/nearby_browse.hpp"

#ifdef UMF_WITH_AVAHI
#include "native/screen_discovery.hpp"
#endif

namespace umf::provider {

NearbyBrowse::NearbyBrowse(Settings settings, std::shared_ptr<NearbyScreens> screens)
    : settings_(std::move(settings)), screens_(std::move(screens)), thread_([this] { run(); }) {}

NearbyBrowse::~NearbyBrowse() {
    {
        std::lock_guard lock(mutex_);
        stopping_ = true;
    }
    wake_.notify_all();
    thread_.join();
}

void NearbyBrowse::run() {
    const auto tell = [this](const std::vector<NearbyScreen>& list, const std::string& why_not) {
        if (settings_.changed) settings_.changed(list, why_not);
    };
#ifdef UMF_WITH_AVAHI
    bool told_unreachable = false;
    std::unique_lock lock(mutex_);
    while (!stopping_) {
        lock.unlock();
        try {
            const auto list =
                nearby_from(native::screens_from(native::browse_screens(settings_.browse_timeout_s)),
                            settings_.own_fingerprint);
            told_unreachable = false;
            if (screens_->set(list)) tell(list, {});
        } catch (const native::AvahiUnreachable& e) {
            // The daemon may come back; what it said before is stale now.
            screens_->set({});
            if (!told_unreachable) tell({}, std::string("the Avahi daemon does not answer (") + e.what() + ")");
            told_unreachable = true;
        }
        lock.lock();
        wake_.wait_for(lock, settings_.period, [this] { return stopping_; });
    }
#else
    tell({}, "this build has no libavahi-client");
#endif
}

}  // namespace umf::provider
