// The native-messaging host's one job: relay between the extension (on its
// standard input and output, framed) and the provider's browser link (JSON
// lines), checking each message on the way. The host adds the browser's
// process id to the extension's hello; it keeps the last hello and windows
// report and sends them again whenever it (re)connects, so a provider
// started after the browser still learns the browser's windows.
#pragma once

#include <filesystem>
#include <ostream>

namespace umf::browser {

struct RelayOptions {
    int from_browser = 0;  // the extension's messages
    int to_browser = 1;
    int browser_pid = 0;   // told to the provider in the hello
    std::filesystem::path runtime_dir;  // where the provider's socket is looked for
    int retry_ms = 2000;   // between attempts to reach a provider
};

// Runs until the browser closes the host's input. Returns 0 then, 1 on a
// message the framing cannot take (the browser is told nothing more).
int run_relay(const RelayOptions& options, std::ostream& log);

}  // namespace umf::browser
