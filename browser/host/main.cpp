// umf-browser-host: the browser companion's native-messaging host. The
// browser starts it when the umf extension connects (the host manifests that
// `umf-provider browser install` writes name it) and it relays between the
// extension and the running provider (host_relay.hpp).
#include <signal.h>
#include <unistd.h>

#include <cstring>
#include <iostream>

#include "browser/host/host_relay.hpp"
#include "shared/io/runtime_dir.hpp"

int main(int argc, char** argv) {
    // Browsers pass the caller's origin (and on Windows a window handle);
    // a person who runs it by hand gets told what it is.
    if (argc > 1 && (std::strcmp(argv[1], "--help") == 0 || std::strcmp(argv[1], "-h") == 0)) {
        std::cout << "umf-browser-host: the umf browser companion's native-messaging host\n"
                     "\n"
                     "usage:\n"
                     "  umf-browser-host ORIGIN      (as a browser starts it)\n"
                     "  umf-browser-host --version\n"
                     "  umf-browser-host --help\n"
                     "\n"
                     "Browsers start it for the umf extension; it relays between the extension and the\n"
                     "running umf-provider (the page each window shows; never a private window's).\n"
                     "Set it up with: umf-provider browser install\n";
        return 0;
    }
    if (argc > 1 && std::strcmp(argv[1], "--version") == 0) {
        std::cout << "umf-browser-host " << UMF_VERSION << "\n";
        return 0;
    }
    if (::isatty(STDIN_FILENO)) {
        std::cerr << "umf-browser-host: started by hand; it talks to a browser on its standard input and output "
                     "(see --help)\n";
        return 2;
    }
    ::signal(SIGPIPE, SIG_IGN);
    umf::browser::RelayOptions options;
    options.browser_pid = static_cast<int>(::getppid());
    options.runtime_dir = umf::runtime_dir();
    return umf::browser::run_relay(options, std::cerr);
}
