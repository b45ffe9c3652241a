#include "provider/desktop/gnome/gnome_window_watch.hpp"

#include <algorithm>
#include <cmath>
#include <thread>

#include "provider/desktop/gnome/gnome_shell_client.hpp"
#include "provider/desktop/window_placement.hpp"

namespace umf::provider {

GnomeNewWindowWatch::GnomeNewWindowWatch(std::shared_ptr<const GnomeShellClient> shell, WindowPlacement placement)
    : shell_(std::move(shell)), placement_(placement) {
    for (const auto& window : shell_->windows()) before_.push_back(window.id);
}

std::optional<unsigned long> GnomeNewWindowWatch::place(int child_pid, std::chrono::milliseconds wait) {
    const auto deadline = std::chrono::steady_clock::now() + wait;
    for (;;) {
        std::optional<WindowInfo> chosen;
        try {
            for (const auto& window : shell_->windows()) {
                if (std::find(before_.begin(), before_.end(), window.id) != before_.end() || window.rect.empty()) continue;
                if (window.pid > 0 && descends_from(window.pid, child_pid)) {
                    chosen = window;
                    break;
                }
                if (!chosen) chosen = window;
            }
        } catch (const DesktopError&) {
            return std::nullopt;  // the shell went away: nothing to move
        }
        if (chosen) {
            const PlaceRect to = centred_on(chosen->rect.width, chosen->rect.height, placement_.x, placement_.y,
                                            placement_.screen);
            const int x = to.x, y = to.y;
            // A window that has just appeared may still be placed by Mutter
            // after the move: it is moved again until it stays.
            try {
                const auto settle = std::chrono::steady_clock::now() + std::chrono::seconds(1);
                while (shell_->move_window(chosen->id, x, y)) {
                    std::this_thread::sleep_for(std::chrono::milliseconds(100));
                    for (const auto& window : shell_->windows())
                        if (window.id == chosen->id && window.rect.x == x && window.rect.y == y) return chosen->id;
                    if (std::chrono::steady_clock::now() >= settle) return chosen->id;
                }
            } catch (const DesktopError&) {
            }
            return std::nullopt;
        }
        if (std::chrono::steady_clock::now() >= deadline) return std::nullopt;
        std::this_thread::sleep_for(std::chrono::milliseconds(50));
    }
}

}  // namespace umf::provider
