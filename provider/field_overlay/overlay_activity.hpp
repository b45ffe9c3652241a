// The overlay hearing the requesters: a seeking or aiming requester brings an
// on-demand field up, an aim moves the aim ring (with the title of what a
// grab would take) and the focus region to where it points, and a requester
// that seeks again (it lost its lock) or leaves takes its ring away. The service calls in from the server's
// threads; everything is handed to the manager's (Qt) thread.
#pragma once

#include <map>
#include <mutex>
#include <optional>
#include <vector>

#include "provider/common/activity.hpp"
#include "provider/field_overlay/overlay_manager.hpp"

namespace umf::provider {

class OverlayActivity : public ActivityListener {
public:
    // `screen_indices[i]`: the manager's index of the welcome's screen i.
    // The manager must outlive the server that calls this.
    OverlayActivity(OverlayManager* manager, std::vector<int> screen_indices);

    // The screens changed: the new welcome's screen i is the manager's index
    // screen_indices[i].
    void set_screen_indices(std::vector<int> screen_indices);

    void seeking(std::uint64_t session) override;
    void aimed(const AimActivity& aim) override;
    void left(std::uint64_t session) override;

private:
    // The screen of the session's ring, which it no longer has.
    std::optional<int> take_aim_mark(std::uint64_t session);

    OverlayManager* manager_;
    std::mutex mutex_;
    std::vector<int> screen_indices_;
    std::map<std::uint64_t, int> aim_mark_screen_;  // session -> manager index of its ring
};

}  // namespace umf::provider
