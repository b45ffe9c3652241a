// `umf-provider trust`: the screen's root, the certificate authority whose
// serving certificate phones and browsers can trust without a warning
// (trust/root_authority.hpp): its fingerprint and where phones get it;
// `trust export FILE [--der | --mobileconfig]` writes it.
#pragma once

#include <iostream>

#include "shared/cli/args.hpp"

namespace umf::provider {

// Options: config-dir, port, host; flags: der, mobileconfig. Exit codes:
// 0, 2 wrong usage, 3 the root or FILE cannot be read or written.
int run_trust(const cli::Args& args, std::ostream& out = std::cout, std::ostream& err = std::cerr);

}  // namespace umf::provider
