// `umf-provider pair`: the pairing URL as text and as a QR code;
// `umf-provider share`: pin a file or URL to a screen region of the running
// provider;
// `umf-provider puts`: the puts waiting for an answer at the running
// provider, and answering one (--accept ID [--open] [--always], --dismiss ID).
#pragma once

#include <iostream>

#include "shared/cli/args.hpp"

namespace umf::provider {

int run_pair(const cli::Args& args);
int run_share(const cli::Args& args);
// Options: port, accept, dismiss; flags: open, always, json. Exit codes as
// share: 0, 2 wrong usage, 3 the provider refused (no such put), 4 no
// provider running.
int run_puts(const cli::Args& args, std::ostream& out = std::cout, std::ostream& err = std::cerr);

}  // namespace umf::provider
