#include "provider/commands/serve_parts.hpp"

#include <unistd.h>

#include <QGuiApplication>
#include <QScreen>
#include <chrono>
#include <iostream>
#include <thread>

#include "provider/browser/browser_link.hpp"
#include "provider/browser/browser_resolver.hpp"
#include "provider/content/shared_items_file.hpp"
#include "provider/content/snapshot_resolver.hpp"
#include "provider/content/window_resolver.hpp"
#include "provider/field_overlay/overlay_manager.hpp"
#include "provider/put/put_folder.hpp"
#include "provider/put/trusted_devices.hpp"

namespace umf::provider {

using cli::get;
using cli::UsageError;

PutChoice put_choice(const cli::Args& a, const std::filesystem::path& config_dir, bool public_mode) {
    // Kiosks take no puts unless told (a shared-photo wall: --public --puts always).
    PutChoice c;
    c.mode = get(a, "puts").value_or(public_mode ? "never" : "ask");
    if (c.mode != "ask" && c.mode != "always" && c.mode != "never")
        throw UsageError("--puts takes ask, always or never, not '" + c.mode + "'");
    c.settings.folder = get(a, "put-dir") ? std::filesystem::path(*get(a, "put-dir")) : default_put_folder();
    c.settings.trusted_devices = config_dir / kTrustedDevicesFile;
    if (const auto mb = get(a, "put-max-mb")) {
        // Whole megabytes (10^6 bytes), up to 1 TB: a wall of photos wants a few, a desk gigabytes.
        if (mb->empty() || mb->size() > 7 || mb->find_first_not_of("0123456789") != std::string::npos ||
            std::stoll(*mb) < 1 || std::stoll(*mb) > 1'000'000)
            throw UsageError("--put-max-mb takes a whole number of megabytes from 1 to 1000000, not '" + *mb + "'");
        c.settings.max_bytes = std::stoll(*mb) * 1'000'000;
    }
    return c;
}

PutAnswerers put_answerers(const PutChoice& puts, bool headless, OverlayManager* overlay) {
    PutAnswerers out;
    if (puts.mode == "always") {
        out.decider = std::make_shared<FixedPutDecider>(PutAnswer::save);
    } else if (puts.mode == "ask") {
        out.control = std::make_shared<ControlPutDecider>();
        out.decider = out.control;
        if (!headless) {
            // The welcome's screen i is the manager's screen layout_indices()[i]; one screen otherwise.
            out.prompt = std::make_shared<PutPromptDecider>(
                std::chrono::duration_cast<std::chrono::seconds>(puts.settings.answer_timeout),
                [overlay](int index) -> QScreen* {
                    if (!overlay) return QGuiApplication::primaryScreen();
                    const auto indices = overlay->layout_indices();
                    if (index < 0 || index >= static_cast<int>(indices.size())) return nullptr;
                    for (const OverlayScreen& s : overlay->screens())
                        if (s.index == indices[index])
                            for (QScreen* q : QGuiApplication::screens())
                                if (q->name() == s.name) return q;
                    return nullptr;
                });
            out.decider = std::make_shared<FirstAnswerDecider>(
                std::vector<std::shared_ptr<PutDecider>>{out.prompt, out.control});
            // The cards stay over the field, which raises itself over new windows.
            if (overlay)
                overlay->set_windows_over_field([cards = std::weak_ptr<PutPromptDecider>(out.prompt)] {
                    const auto c = cards.lock();
                    return c ? c->shown_cards() : std::vector<QWindow*>{};
                });
        }
    }
    return out;
}

void add_window_resolvers(const OpenedDesktop& desktop, OverlayManager* overlay, PutPromptDecider* cards,
                          std::vector<std::shared_ptr<const Resolver>>& resolvers,
                          std::shared_ptr<BrowserLink>& browser_link, std::shared_ptr<BrowserResolver>& browsers) {
    // The windows under the point, never the provider's own.
    const std::shared_ptr<const Desktop> windows = desktop.desktop;
    WindowResolverOptions options;
    options.filter.own_pids.insert(static_cast<int>(::getpid()));
    browser_link = std::make_shared<BrowserLink>();
    browsers = std::make_shared<BrowserResolver>(windows, options.filter, browser_link, &std::cout);
    resolvers.push_back(browsers);
    resolvers.push_back(std::make_shared<WindowResolver>(windows, options));
    auto snapshots = std::make_shared<SnapshotResolver>(windows, options.filter, desktop.abilities.snapshots);
    if (overlay || cards) {
        // A snapshot shows the screen without the field and without the put
        // cards. Called from a server thread; the server stops before the Qt
        // loop does, so the blocking call always returns.
        QObject* qt = QGuiApplication::instance();
        auto set_shown = [overlay, cards, qt](bool shown, Qt::ConnectionType how) {
            QMetaObject::invokeMethod(
                qt,
                [overlay, cards, shown] {
                    if (overlay) shown ? overlay->show_after_snapshot() : overlay->hide_for_snapshot();
                    if (cards) shown ? cards->show_after_snapshot() : cards->hide_for_snapshot();
                },
                how);
        };
        snapshots->set_around_capture(
            [set_shown] {
                set_shown(false, Qt::BlockingQueuedConnection);
                std::this_thread::sleep_for(std::chrono::milliseconds(OverlayManager::kSnapshotSettleMs));
            },
            [set_shown] { set_shown(true, Qt::QueuedConnection); });
    }
    resolvers.push_back(std::move(snapshots));
}

// What was shared before this provider was started again by its keeper
// comes back, and every change is written down for the next one.
void keep_shared_items(SharedItems& items, const std::filesystem::path& file) {
    try {
        const int restored = items.restore(load_shared_items(file));
        if (restored > 0) std::cout << "shared: " << restored << " item(s) shared before are served again\n";
    } catch (const std::exception& e) {
        std::cerr << "umf-provider: " << e.what() << "; the items shared before are gone\n";
    }
    items.on_change([file](const std::vector<SharedItem>& now) {
        try {
            save_shared_items(file, now);
        } catch (const std::exception& e) {
            std::cerr << "umf-provider: " << e.what() << "; shared items will not survive a restart\n";
        }
    });
}

}  // namespace umf::provider
