// Placing a put's new window on KWin (desktop/window_placement.hpp's rules):
// the shown windows before the opener starts, then a listing script every
// kPollInterval until a new window appears (preferably one of the child's
// processes), which a second script moves centred on the pointed place.
#pragma once

#include <chrono>
#include <memory>
#include <optional>
#include <vector>

#include "provider/desktop/desktop.hpp"
#include "provider/desktop/kde/kwin_scripting.hpp"
#include "provider/desktop/kde/kwin_scripts.hpp"

namespace umf::provider {

class KdeWindowWatch final : public NewWindowWatch {
public:
    // Lists the windows there now; throws DesktopError when KWin does not
    // answer.
    KdeWindowWatch(std::shared_ptr<const KWinScripting> scripting, const WindowPlacement& where,
                   std::chrono::milliseconds timeout);
    std::optional<unsigned long> place(int child_pid, std::chrono::milliseconds wait) override;

private:
    std::vector<KWinWindow> list() const;

    std::shared_ptr<const KWinScripting> scripting_;
    WindowPlacement where_;
    std::chrono::milliseconds timeout_;
    std::vector<unsigned long> before_;
};

}  // namespace umf::provider
