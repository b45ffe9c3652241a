#include "provider/put/desktop_open.hpp"

#include "provider/desktop/window_placement.hpp"

#include <fcntl.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <memory>
#include <thread>
#include <vector>

extern char** environ;

namespace umf::provider {

bool open_with_desktop(const std::string& target, std::string* problem, std::unique_ptr<NewWindowWatch> owned) {
    auto fail = [&](std::string why) {
        if (problem) *problem = std::move(why);
        return false;
    };
    if (target.empty() || target[0] == '-') return fail("not a URL or an absolute path: " + target);
    std::shared_ptr<NewWindowWatch> watch = std::move(owned);
    posix_spawn_file_actions_t actions;
    if (posix_spawn_file_actions_init(&actions) != 0) return fail("cannot prepare xdg-open");
    // No terminal input for it; its output is of no use to the provider's console.
    posix_spawn_file_actions_addopen(&actions, 0, "/dev/null", O_RDONLY, 0);
    posix_spawn_file_actions_addopen(&actions, 1, "/dev/null", O_WRONLY, 0);
    std::string program = "xdg-open";
    std::string argument = target;
    std::vector<char*> argv{program.data(), argument.data(), nullptr};
    pid_t pid = 0;
    const int rc = posix_spawnp(&pid, "xdg-open", &actions, nullptr, argv.data(), environ);
    posix_spawn_file_actions_destroy(&actions);
    if (rc != 0) return fail(std::string("cannot start xdg-open: ") + std::strerror(rc));
    if (watch) std::thread([watch, pid] { watch->place(pid, std::chrono::milliseconds(kPlacementWaitMs)); }).detach();
    // Reaped when it ends, however long the browser keeps it.
    std::thread([pid] {
        int status = 0;
        while (::waitpid(pid, &status, 0) < 0 && errno == EINTR) {
        }
    }).detach();
    return true;
}

}  // namespace umf::provider
