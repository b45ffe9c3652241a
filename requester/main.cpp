// umf-requester: the webcam client's command line. A small dispatcher: each
// command lives in its own file with its own usage text.
#include <csignal>
#include <cstdio>
#include <cstring>
#include <exception>
#include <new>
#include <string>

#include <opencv2/core.hpp>
#include <opencv2/core/utils/logger.hpp>

#include "requester/cli.hpp"
#include "requester/discover_command.hpp"
#include "requester/grab_command.hpp"
#include "requester/locate_command.hpp"
#include "requester/pair_command.hpp"
#include "requester/put_command.hpp"
#include "shared/field/field_io.hpp"

namespace {

using namespace umf::requester;

const char* kUsageText = R"(umf-requester: find the marker field in camera frames and tell which field point is aimed at

usage:
  umf-requester locate --field F.json [--sequence] [--aim X,Y] IMAGE... | --video FILE
  umf-requester grab [--url URL] [--camera I | --video FILE | --image FILE]
                     [--out DIR] [--open] [--auto] [--no-window] [--timeout S] [--no-switch]
  umf-requester put FILE|LINK [--url URL] [--title TEXT]
                    [--camera I | --video FILE | --image FILE] [--auto] [--no-window] [--timeout S]
                    [--no-switch]
  umf-requester pair URL | --list | --forget NAME|URL
  umf-requester discover [--timeout S] [--json] [--url URL]
  umf-requester help [COMMAND]
  umf-requester COMMAND --help

locate    finds the field in image files or the frames of a video and prints one JSON
          line per frame: the field point under the image centre (or --aim), the
          image -> field homography, and how sure the detector is.
grab      connects to a provider (its pairing URL), finds its field in the camera,
          a video or a photo, and takes what the screen shows under the image
          centre: prints a link, downloads a file. One JSON line at the end.
put       the other way round: gives the screen a file or a link where the camera
          points; the person at the screen accepts it. One JSON line at the end.
pair      keeps a screen's pairing URL: grab and put then need no --url, and
          switch to a kept screen when it is the one in view.
discover  lists the screens that announce themselves on the local network (DNS-SD
          through Avahi): name, https://HOST.local:PORT, addresses and the root's
          fingerprint, one line each (--json: one JSON object each).

exit codes: 0 the command ran (locate: frames without the field are reported, not
            failed; grab and put: something was grabbed or put; discover: a
            screen was found); 2 wrong usage; 3 an input could not be read, or
            the output could not be written (discover: built without Avahi);
            grab and put: 4 the provider could not be reached, its certificate
            or token did not match, or the exchange failed; 5 nothing was
            grabbed or put (no field in view, nothing there, refused);
            discover: 4 the Avahi daemon could not be asked; 5 no screen answered.
)";

struct Command {
    const char* name;
    const char* usage;
    int (*run)(int argc, char** argv);  // argv[2..] are the command's arguments
};

int locate(int argc, char** argv) { return run_locate(parse_locate_args(argc, argv, 2), stdout); }

// grab and put promise a JSON line on stdout whatever happens, wrong usage included.
int grab(int argc, char** argv) {
    GrabOptions options;
    try {
        options = parse_grab_args(argc, argv, 2);
    } catch (const UsageError& e) {
        write_usage_failure(stdout, e.what());
        throw;
    }
    return run_grab(options, stdout);
}

int put(int argc, char** argv) {
    PutOptions options;
    try {
        options = parse_put_args(argc, argv, 2);
    } catch (const UsageError& e) {
        write_usage_failure(stdout, e.what());
        throw;
    }
    return run_put(options, stdout);
}

int discover(int argc, char** argv) { return run_discover(parse_discover_args(argc, argv, 2), stdout); }

int pair(int argc, char** argv) { return run_pair(parse_pair_args(argc, argv, 2), stdout); }

const Command kCommands[] = {
    {"locate", kLocateUsage, locate},
    {"grab", kGrabUsage, grab},
    {"put", kPutUsage, put},
    {"discover", kDiscoverUsage, discover},
    {"pair", kPairUsage, pair},
};

const Command* find_command(const std::string& name) {
    for (const auto& c : kCommands)
        if (name == c.name) return &c;
    return nullptr;
}

bool asks_for_help(int argc, char** argv) {
    for (int i = 2; i < argc; ++i) {
        if (std::strcmp(argv[i], "--") == 0) return false;
        if (std::strcmp(argv[i], "--help") == 0 || std::strcmp(argv[i], "-h") == 0) return true;
    }
    return false;
}

}  // namespace

int main(int argc, char** argv) {
    if (argc < 2) {
        std::fputs(kUsageText, stderr);
        return kUsage;
    }
    // Our own messages say what went wrong; OpenCV's backend chatter
    // ("[ WARN:0@...] global cap_gstreamer ...") only confuses.
    cv::utils::logging::setLogLevel(cv::utils::logging::LOG_LEVEL_ERROR);
    // Large transfers write to the socket with blocking calls (blocking_tls.hpp):
    // a provider that goes away mid-write is an EPIPE to report, not a signal
    // that ends the program.
    std::signal(SIGPIPE, SIG_IGN);
    const std::string cmd = argv[1];
    try {
        if (cmd == "help" || cmd == "--help" || cmd == "-h") {
            if (argc > 3) throw UsageError("help takes at most one command");
            if (argc == 3) {
                const Command* c = find_command(argv[2]);
                if (!c) throw UsageError("unknown command '" + std::string(argv[2]) + "'");
                std::fputs(c->usage, stdout);
            } else {
                std::fputs(kUsageText, stdout);
            }
            return kOk;
        }
        if (cmd == "--version") {
            std::puts("umf-requester " UMF_VERSION);
            return kOk;
        }
        const Command* c = find_command(cmd);
        if (!c) {
            std::fprintf(stderr, "umf-requester: unknown command '%s'\n\n", cmd.c_str());
            std::fputs(kUsageText, stderr);
            return kUsage;
        }
        if (asks_for_help(argc, argv)) {
            std::fputs(c->usage, stdout);
            return kOk;
        }
        return c->run(argc, argv);
    } catch (const UsageError& e) {
        std::fprintf(stderr, "umf-requester: %s\n(umf-requester --help lists the commands and options)\n", e.what());
        return kUsage;
    } catch (const umf::FieldFileError& e) {
        std::fprintf(stderr, "umf-requester: %s\n", e.what());
        return kInputError;
    } catch (const InputError& e) {
        std::fprintf(stderr, "umf-requester: %s\n", e.what());
        return kInputError;
    } catch (const std::bad_alloc&) {
        std::fprintf(stderr, "umf-requester: out of memory\n");
        return kInputError;
    } catch (const std::exception& e) {
        std::fprintf(stderr, "umf-requester: error: %s\n", e.what());
        return kInputError;
    }
}
