// Named steps of `umf-provider serve` (serve_command.cpp composes them):
// the put settings from the command line, who answers puts, the resolvers
// that look into a desktop's windows, the web client's folder and the
// shared items kept across restarts.
#pragma once

#include <filesystem>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "provider/content/resolver.hpp"
#include "provider/content/shared_items.hpp"
#include "provider/desktop/open_desktop.hpp"
#include "provider/put/put_deciders.hpp"
#include "provider/put/put_prompt_window.hpp"
#include "shared/cli/args.hpp"

namespace umf::provider {

class BrowserLink;
class BrowserResolver;
class OverlayManager;

// --puts (ask, always, never; default never in public mode, else ask),
// --put-dir and --put-max-mb; the trusted devices' file in `config_dir`.
// Throws UsageError.
struct PutChoice {
    std::string mode;
    PutSettings settings;
};
PutChoice put_choice(const cli::Args& a, const std::filesystem::path& config_dir, bool public_mode);

// Who answers puts. Made before the server and released after it, on the
// Qt thread. `decider` null: no puts, and no "put" in the welcome.
struct PutAnswerers {
    std::shared_ptr<ControlPutDecider> control;  // `umf-provider puts`
    std::shared_ptr<PutPromptDecider> prompt;    // the card at the pointed place (on a desktop)
    std::shared_ptr<PutDecider> decider;
};
PutAnswerers put_answerers(const PutChoice& puts, bool headless, OverlayManager* overlay);

// The resolvers for a desktop's windows, in order: the browser companion's
// (a browser window's page), the window's document, its snapshot (with the
// field and the put cards hidden while it is taken). Appended to
// `resolvers`; `browser_link` and `browsers` are set for the server to
// listen on and for puts to open tabs. Throws when the windows cannot be
// looked up.
void add_window_resolvers(const OpenedDesktop& desktop, OverlayManager* overlay, PutPromptDecider* cards,
                          std::vector<std::shared_ptr<const Resolver>>& resolvers,
                          std::shared_ptr<BrowserLink>& browser_link, std::shared_ptr<BrowserResolver>& browsers);


// What was shared before this provider was started again by its keeper
// comes back from `file`, and every change is written there for the next one.
void keep_shared_items(SharedItems& items, const std::filesystem::path& file);

}  // namespace umf::provider
