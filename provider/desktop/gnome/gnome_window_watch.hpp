// Placing a put's window on GNOME Shell: the windows before the opener
// starts, then for a while the first new one (preferably of the opener's
// processes), moved by the extension so it is centred on the pointed place
// and kept inside that monitor.
#pragma once

#include <memory>
#include <vector>

#include "provider/desktop/desktop.hpp"

namespace umf::provider {

class GnomeShellClient;

class GnomeNewWindowWatch final : public NewWindowWatch {
public:
    // Takes the windows there now; throws DesktopError when they cannot be
    // listed.
    GnomeNewWindowWatch(std::shared_ptr<const GnomeShellClient> shell, WindowPlacement placement);
    std::optional<unsigned long> place(int child_pid, std::chrono::milliseconds wait) override;

private:
    std::shared_ptr<const GnomeShellClient> shell_;
    WindowPlacement placement_;
    std::vector<unsigned long> before_;
};

}  // namespace umf::provider
