// Opening a URL or a file with the desktop's default application: `xdg-open
// TARGET`, found on PATH and started without a shell (posix_spawnp), fire and
// forget; a thread of its own reaps the child when it ends. Tests put a fake
// xdg-open first on PATH that records its argument. With the desktop's watch
// (Desktop::watch_new_window), the window it brings up is moved to the pointed
// place (desktop/window_placement.hpp), best effort.
#pragma once

#include <memory>
#include <optional>
#include <string>

#include "provider/desktop/window_placement.hpp"

namespace umf::provider {

// True when xdg-open was started (not whether it found an application);
// false with the reason in `problem` otherwise. The target goes as the one
// argument; one that starts with '-' is refused, so it is never an option.
// `watch`, made before xdg-open starts (it notes the windows there), moves
// the window xdg-open brings up; nullptr: nothing is moved.
bool open_with_desktop(const std::string& target, std::string* problem = nullptr,
                       std::unique_ptr<NewWindowWatch> watch = nullptr);

}  // namespace umf::provider
