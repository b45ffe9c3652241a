// "First, do no harm" on a Wayland compositor that has no umf backend: a
// real weston, headless, with Xwayland, and a real provider started as in
// such a session (WAYLAND_DISPLAY, DISPLAY of Xwayland, XDG_SESSION_TYPE).
// No overlay window may exist, so no click can be swallowed, and the
// console says what works there; the provider keeps serving.
#if defined(UMF_PROVIDER_TESTS)

#include <gtest/gtest.h>
#include <sys/stat.h>

#include <filesystem>
#include <fstream>
#include <string>
#include <sstream>
#include <thread>

#include "tests/support/files.hpp"
#include "tests/support/temp_dir.hpp"
#include "tests/support/x11_session.hpp"

namespace {

namespace fs = std::filesystem;
using namespace umf::test;

TEST(WaylandSession, ACompositorWithoutABackendGetsNoOverlayAndIsToldWhatWorks) {
    for (const char* program : {"weston", "Xwayland", "xwininfo", "xterm"})
        if (!find_program(program))
            GTEST_SKIP() << program << " is not installed (Debian: apt-get install -y weston xwayland x11-utils xterm)";
    TempDir dir;
    const fs::path runtime = dir.path / "runtime";
    fs::create_directories(runtime);
    ::chmod(runtime.c_str(), 0700);
    const std::string socket = "umf-weston";
    Process::Options options;
    options.env = environment_with({{"XDG_RUNTIME_DIR", runtime.string()}});
    options.log = dir.path / "weston.log";
    // Xwayland starts on demand; weston says which display it listens on.
    Process weston({"weston", "--backend=headless-backend.so", "--xwayland", "--socket=" + socket, "--width=1280",
                    "--height=720", "--idle-time=0"},
                   options);
    std::string display;
    ASSERT_TRUE(wait_until(
        [&] {
            const std::string log = read_file(dir.path / "weston.log");
            const auto at = log.find("xserver listening on display ");
            if (at == std::string::npos) return false;
            display = log.substr(at + 29, log.find('\n', at) - at - 29);
            return fs::exists(runtime / socket);
        },
        15s))
        << "weston did not start:\n" << read_file(dir.path / "weston.log");

    const auto session = environment_with({{"XDG_RUNTIME_DIR", runtime.string()},
                                           {"WAYLAND_DISPLAY", socket},
                                           {"DISPLAY", display},
                                           {"XDG_SESSION_TYPE", "wayland"},
                                           {"XDG_CURRENT_DESKTOP", "weston"},
                                           {"QT_QPA_PLATFORM", "xcb"},
                                           {"XDG_CONFIG_HOME", (dir.path / "config").string()}});
    // An X11 client below where an overlay would be.
    options.env = session;
    options.log = dir.path / "xterm.log";
    Process xterm({"xterm", "-title", "umf-weston-xterm", "-geometry", "80x24+0+0"}, options);
    ASSERT_TRUE(wait_until([&] { return run({"xwininfo", "-root", "-tree"}, session).find("umf-weston-xterm") != std::string::npos; }, 15s))
        << "xterm did not come up";

    options.log = dir.path / "provider.log";
    Process provider({UMF_PROVIDER_TOOL, "--port", "0", "--no-qr", "--config-dir", (dir.path / "umf").string(),
                      "--preset", "static"},
                     options);
    ASSERT_TRUE(wait_until([&] { return read_file(dir.path / "provider.log").find("desktop: ") != std::string::npos; }, 20s))
        << read_file(dir.path / "provider.log");
    // Give a wrongly made overlay time to be mapped before looking.
    std::this_thread::sleep_for(1s);
    const std::string log = read_file(dir.path / "provider.log");
    EXPECT_NE(log.find("desktop: wayland (no backend)"), std::string::npos) << log;
    EXPECT_NE(log.find("no field is shown"), std::string::npos) << log;
    EXPECT_NE(log.find("puts work"), std::string::npos) << log;
    EXPECT_NE(log.find("pairing URL: https://"), std::string::npos) << "not serving:\n" << log;
    const std::string tree = run({"xwininfo", "-root", "-tree"}, session);
    EXPECT_EQ(tree.find("umf overlay"), std::string::npos) << tree;
    EXPECT_EQ(tree.find("umf aim mark"), std::string::npos) << tree;
    // No window of the provider's is mapped at all on the compositor's
    // Xwayland but the invisible ones Qt keeps for itself (1x1..3x3), so no
    // click can land on one.
    std::istringstream lines(tree);
    for (std::string line; std::getline(lines, line);)
        if (line.find("umf") != std::string::npos && line.find("umf-weston-xterm") == std::string::npos) {
            EXPECT_NE(line.find("Qt Selection Owner"), std::string::npos) << line;
        }
    EXPECT_FALSE(provider.wait_exit(0s)) << "the provider stopped:\n" << read_file(dir.path / "provider.log");
}

}  // namespace

#endif
