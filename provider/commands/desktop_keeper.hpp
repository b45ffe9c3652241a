// The provider on a desktop runs in a child process that this one keeps.
// Qt ends a process whose display connection breaks (the X server, or the
// compositor with its Xwayland, died), and that must not end the serving:
// the keeper then says so, serves on without a desktop (boards, shares,
// puts) in a new child, and starts the desktop provider again once the
// display answers. SIGINT and SIGTERM to the keeper go to its child. The
// keeper itself is one thread without Qt, so forking it is safe.
#pragma once

#include <sys/types.h>

#include <chrono>
#include <filesystem>
#include <functional>
#include <optional>
#include <ostream>
#include <variant>

namespace umf::provider {

// What a child of the keeper does.
struct KeeperRole {
    bool with_desktop = true;             // false: serve as --desktop none does
    std::optional<unsigned short> port;   // the port the first child got: later ones take it too
    std::filesystem::path shares_file;    // shared items, kept across children
    int port_report_fd = -1;              // write the listening port here (tell_keeper_port)
};

struct KeeperSettings {
    std::filesystem::path shares_file;
    std::function<bool()> display_answers;          // the display is there again
    std::chrono::milliseconds poll{1000};           // how often the keeper looks
    std::chrono::seconds short_life{30};            // a desktop child that ends sooner is started again later each time
    std::chrono::seconds longest_wait{300};
    std::chrono::seconds stop_grace{10};            // after SIGTERM, then SIGKILL
};

// Returns in every child with its role (the caller serves so and returns
// its exit code from main), and in the keeper once the provider is done,
// with the exit code to end with. Expects SIGINT and SIGTERM blocked.
std::variant<KeeperRole, int> keep_provider(const KeeperSettings& settings, std::ostream& log);

// Called by a child once it listens.
void tell_keeper_port(const KeeperRole& role, unsigned short port);

// How a child ended, for the console: "exit 1", "killed by SIGKILL". A
// provider's own exit codes (0, 2, 3, 4) mean it is done.
struct ChildEnd {
    bool done = false;  // ended as the provider ends: no desktop to bring back
    std::string how;
};
ChildEnd describe_child_end(int wait_status);

}  // namespace umf::provider
