// `umf-provider [serve]`: the provider itself. Headless (no display, or
// --headless) it shows a board on a virtual screen, the built-in demo board
// unless --board names one; on a desktop it serves what lies under the point.
#pragma once

#include <functional>
#include <memory>
#include <optional>
#include <string>

#include "provider/commands/desktop_keeper.hpp"
#include "shared/cli/args.hpp"

namespace umf::provider {

class OverlayManager;

// The controls for a running provider (the tray, the tuning window), kept
// alive while it runs.
class ProviderControls {
public:
    virtual ~ProviderControls() = default;
    // What works on this desktop changed (an extension stopped or came back).
    virtual void set_status(const std::string& status) = 0;
};

// What the executable adds on a desktop (Qt Widgets live outside the core).
struct ServeHooks {
    // `overlay` null: the desktop shows no field, and the tray says so in
    // `status` (what works here). `tune`: open the tuning window now.
    std::function<std::shared_ptr<ProviderControls>(OverlayManager* overlay, const std::string& status,
                                        const std::string& presets_file, const std::string& pairing_url, bool tune)>
        desktop_controls;
    // Set when a keeper runs this provider (commands/desktop_keeper.hpp):
    // it is told the port, and the shared items outlive this process.
    std::optional<KeeperRole> keeper;
};

extern const char* const kServeOptions[];
extern const char* const kServeFlags[];

// Needs a QGuiApplication (main makes it). Returns the exit code after
// SIGINT or SIGTERM.
int run_serve(const cli::Args& args, const ServeHooks& hooks = {});

}  // namespace umf::provider
