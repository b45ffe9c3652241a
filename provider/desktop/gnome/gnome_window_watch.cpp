#include "desktop/gnome/gnome_window_watch.hpp"

#include <algorithm>
#include <cmath>
#include <fstream>
#include <sstream>
#include <thread>

#include "desktop/gnome/gnome_shell_client.hpp"

namespace umf::provider {

namespace {

int parent_of(int pid) {
    std::ifstream stat("/proc/" + std::to_string(pid) + "/stat");
    std::string line;
    if (!std::getline(stat, line)) return 0;
    // The command name may hold spaces and parentheses: fields follow the last ')'.
    const auto close = line.rfind(')');
    if (close == std::string::npos) return 0;
    std::istringstream rest(line.substr(close + 1));
    char state = 0;
    int parent = 0;
    rest >> state >> parent;
    return parent;
}

}  // namespace

std::pair<int, int> centred_in(int width, int height, double x, double y, const WindowRect& screen) {
    int left = static_cast<int>(std::lround(x - width / 2.0));
    int top = static_cast<int>(std::lround(y - height / 2.0));
    left = std::max(screen.x, std::min(left, screen.x + screen.width - width));
    top = std::max(screen.y, std::min(top, screen.y + screen.height - height));
    return {left, top};
}

bool gnome_descends_from(int pid, int ancestor) {
    for (int hops = 0; pid > 1 && hops < 64; ++hops) {
        if (pid == ancestor) return true;
        pid = parent_of(pid);
    }
    return pid == ancestor && ancestor > 0;
}

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
                if (window.pid > 0 && gnome_descends_from(window.pid, child_pid)) {
                    chosen = window;
                    break;
                }
                if (!chosen) chosen = window;
            }
        } catch (const DesktopError&) {
            return std::nullopt;  // the shell went away: nothing to move
        }
        if (chosen) {
            const auto [x, y] = centred_in(chosen->rect.width, chosen->rect.height, placement_.x, placement_.y,
                                           placement_.screen);
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
