#include "requester/open_url.hpp"

#include <fcntl.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cstdio>
#include <cstring>

extern char** environ;

namespace umf::requester {

// The child gets our stderr for both its outputs: a browser started by
// xdg-open must not hold our stdout (the JSON line's reader would wait for it
// to close) nor read our stdin.
bool open_url(const std::string& url) {
    posix_spawn_file_actions_t actions;
    posix_spawn_file_actions_init(&actions);
    posix_spawn_file_actions_addopen(&actions, STDIN_FILENO, "/dev/null", O_RDONLY, 0);
    posix_spawn_file_actions_adddup2(&actions, STDERR_FILENO, STDOUT_FILENO);
    std::string program = "xdg-open";
    std::string arg = url;
    char* argv[] = {program.data(), arg.data(), nullptr};
    pid_t pid = 0;
    const int rc = posix_spawnp(&pid, "xdg-open", &actions, nullptr, argv, environ);
    posix_spawn_file_actions_destroy(&actions);
    if (rc != 0) {
        std::fprintf(stderr, "umf-requester: cannot run xdg-open: %s\n", std::strerror(rc));
        return false;
    }
    // xdg-open hands over to the browser and exits; a browser it runs
    // directly is not waited for beyond a few seconds.
    for (int i = 0; i < 50; ++i) {
        int status = 0;
        const pid_t r = waitpid(pid, &status, WNOHANG);
        if (r == pid) {
            if (WIFEXITED(status) && WEXITSTATUS(status) == 0) return true;
            std::fprintf(stderr, "umf-requester: xdg-open could not open the link (exit status %d)\n",
                         WIFEXITED(status) ? WEXITSTATUS(status) : -1);
            return false;
        }
        if (r < 0) return false;
        usleep(100 * 1000);
    }
    return true;
}

}  // namespace umf::requester
