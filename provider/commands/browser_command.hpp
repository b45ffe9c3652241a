// `umf-provider browser install`: the browser companion's host manifests for
// Chromium, Chrome, Edge and Firefox (per user, or --system under --prefix),
// and how to load the extension;
// `umf-provider browser status`: the browsers connected to the running
// provider and the page each window shows.
#pragma once

#include <iostream>

#include "shared/cli/args.hpp"

namespace umf::provider {

// Words: install | status. Options: host, prefix (install), port (status);
// flags: system (install), json (status). Exit codes as `puts`.
int run_browser(const cli::Args& args, std::ostream& out = std::cout, std::ostream& err = std::cerr);

}  // namespace umf::provider
