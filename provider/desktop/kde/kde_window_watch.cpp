#include "provider/desktop/kde/kde_window_watch.hpp"

#include <algorithm>
#include <map>
#include <thread>

#include "provider/desktop/window_placement.hpp"

namespace umf::provider {

namespace {

constexpr std::chrono::milliseconds kPollInterval{100};

std::vector<unsigned long> ids_of(const std::vector<KWinWindow>& windows) {
    std::vector<unsigned long> ids;
    for (const auto& w : windows) ids.push_back(window_id(w.uuid));
    return ids;
}

}  // namespace

KdeWindowWatch::KdeWindowWatch(std::shared_ptr<const KWinScripting> scripting, const WindowPlacement& where,
                               std::chrono::milliseconds timeout)
    : scripting_(std::move(scripting)), where_(where), timeout_(timeout), before_(ids_of(list())) {}

std::vector<KWinWindow> KdeWindowWatch::list() const {
    const auto windows = parse_window_list(scripting_->run(list_windows_script(), timeout_));
    if (!windows) throw DesktopError("KWin's window list could not be read");
    return *windows;
}

std::optional<unsigned long> KdeWindowWatch::place(int child_pid, std::chrono::milliseconds wait) {
    const auto deadline = std::chrono::steady_clock::now() + wait;
    for (;;) {
        std::vector<KWinWindow> now;
        try {
            now = list();
        } catch (const DesktopError&) {
            return std::nullopt;  // KWin went away: nothing to move
        }
        std::map<unsigned long, const KWinWindow*> by_id;
        for (const auto& w : now) by_id[window_id(w.uuid)] = &w;
        const auto picked = pick_new_window(
            before_, ids_of(now),
            [&](unsigned long id) { return by_id[id]->pid > 0 && descends_from(by_id[id]->pid, child_pid); },
            [](unsigned long) { return true; });  // the list holds only normal windows and dialogs
        if (picked) {
            const KWinWindow& window = *by_id[*picked];
            const WindowRect rect =
                centred_on(window.rect.width, window.rect.height, where_.x, where_.y, where_.screen);
            try {
                if (scripting_->run(move_window_script(window.uuid, rect), timeout_) == "moved") return picked;
            } catch (const DesktopError&) {
            }
            return std::nullopt;
        }
        if (std::chrono::steady_clock::now() + kPollInterval > deadline) return std::nullopt;
        std::this_thread::sleep_for(kPollInterval);
    }
}

}  // namespace umf::provider
