#include "provider/desktop/wlroots/sway_new_window_watch.hpp"

#include <cstdlib>
#include <iostream>
#include <thread>

#include "provider/desktop/window_placement.hpp"
#include "provider/desktop/wlroots/sway_ipc.hpp"
#include "provider/desktop/wlroots/sway_tree.hpp"

namespace umf::provider {

namespace {

constexpr std::chrono::milliseconds kPollEvery{100};

void debug(const std::string& line) {
    if (std::getenv("UMF_DEBUG")) std::cerr << "umf: placement: " << line << "\n";
}

}  // namespace

std::unique_ptr<SwayNewWindowWatch> SwayNewWindowWatch::create(std::string swaysock, WindowPlacement where) {
    try {
        auto before = sway_window_ids(sway_request(swaysock, SwayMessage::get_tree));
        return std::unique_ptr<SwayNewWindowWatch>(new SwayNewWindowWatch(std::move(swaysock), where, std::move(before)));
    } catch (const DesktopError& e) {
        debug(e.what());
        return nullptr;
    }
}

SwayNewWindowWatch::SwayNewWindowWatch(std::string swaysock, WindowPlacement where, std::vector<unsigned long> before)
    : swaysock_(std::move(swaysock)), where_(where), before_(std::move(before)) {}

std::optional<unsigned long> SwayNewWindowWatch::place(int child_pid, std::chrono::milliseconds wait) {
    const auto deadline = std::chrono::steady_clock::now() + wait;
    try {
        for (;;) {
            const auto tree = sway_request(swaysock_, SwayMessage::get_tree);
            const auto now = sway_window_ids(tree);
            const auto pid_of = [&](unsigned long id) {
                const auto window = sway_window(tree, id);
                return window ? window->pid : 0;
            };
            const auto chosen = pick_new_window(
                before_, now, [&](unsigned long id) { return child_pid > 0 && descends_from(pid_of(id), child_pid); },
                [](unsigned long) { return true; });
            if (chosen) return move(*chosen) ? chosen : std::nullopt;
            if (std::chrono::steady_clock::now() + kPollEvery > deadline) break;
            std::this_thread::sleep_for(kPollEvery);
        }
        debug("no new window within the wait");
    } catch (const DesktopError& e) {
        debug(e.what());
    }
    return std::nullopt;
}

bool SwayNewWindowWatch::move(unsigned long id) const {
    const std::string which = "[con_id=" + std::to_string(id) + "] ";
    sway_run(swaysock_, which + "floating enable");
    // Floating gives it a size of its own: centre that.
    const auto window = sway_window(sway_request(swaysock_, SwayMessage::get_tree), id);
    if (!window) return false;
    const PlaceRect to = centred_on(window->rect.width, window->rect.height, where_.x, where_.y, where_.screen);
    sway_run(swaysock_, which + "move absolute position " + std::to_string(to.x) + " " + std::to_string(to.y));
    debug("moved con " + std::to_string(id) + " to " + std::to_string(to.x) + "," + std::to_string(to.y));
    return true;
}

}  // namespace umf::provider
