// `umf-provider pair`: the pairing URL as text and as a QR code;
// `umf-provider share`: pin a file or URL to a screen region of the running
// provider.
#pragma once

#include "cli/args.hpp"

namespace umf::provider {

int run_pair(const cli::Args& args);
int run_share(const cli::Args& args);

}  // namespace umf::provider
