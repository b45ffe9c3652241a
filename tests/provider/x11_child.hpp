// Tests whose Qt half needs the xcb platform run it in a child process:
// this test binary run again for one disabled test on a fresh Xvfb with
// openbox and a compositing manager. Other tests make an offscreen
// QGuiApplication, at most one exists per process and it cannot change
// platform, while the child starts clean and makes its own on xcb. fork()
// alone would copy the parent's threads' state and maybe its application;
// exec gives a fresh process.
#pragma once

#include <gtest/gtest.h>

#include <QGuiApplication>

#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "provider/desktop/x11/compositor.hpp"
#include "provider/desktop/x11/x11_desktop.hpp"
#include "tests/support/temp_dir.hpp"
#include "tests/support/x11_session.hpp"

namespace umf::test {

// Set in the child's environment: a child test skips without it.
constexpr const char* kX11ChildVariable = "UMF_OVERLAY_TEST_CHILD";

// The child's application, on the xcb platform the parent set.
struct X11ChildApplication {
    int argc = 1;
    char name[16] = "umf_x11_child";
    char* argv[2] = {name, nullptr};
    QGuiApplication app{argc, argv};
};

// Runs the disabled test `child` (its full name, e.g.
// "OverlayWindowOnX.DISABLED_Child") on a fresh Xvfb `screen` with openbox
// and `compositor` running, and checks that it passed; `log` gets its
// output. With `check_detection` the compositor must be seen as running
// only once it runs.
inline void run_x11_child(const std::string& child, const std::string& screen,
                          const std::vector<std::string>& compositor, std::string& log,
                          bool check_detection = false) {
    using namespace std::chrono_literals;
    namespace fs = std::filesystem;
    for (const std::string& program : {std::string("Xvfb"), std::string("openbox"), compositor[0]})
        if (!find_program(program))
            GTEST_SKIP() << program << " is not installed (Debian: apt-get install -y xvfb openbox " << compositor[0] << ")";
    TempDir dir;
    const XServer server = start_xvfb(dir.path / "xvfb.log", screen);
    Process::Options options;
    options.env = environment_with({{"DISPLAY", server.display}, {"QT_QPA_PLATFORM", "xcb"}});
    options.log = dir.path / "openbox.log";
    const auto openbox = start_openbox(options, dir.path / "openbox-ready");
    const provider::X11Desktop desktop(server.display);
    ASSERT_TRUE(desktop.has_ewmh());
    if (check_detection) {
        EXPECT_FALSE(provider::compositor_running(server.display, 0));
    }
    options.log = dir.path / "compositor.log";
    Process running(compositor, options);
    ASSERT_TRUE(wait_until([&] { return provider::compositor_running(server.display, 0); }, 5s));
    if (check_detection) {
        EXPECT_FALSE(provider::compositor_advice().empty());
    }

    options.log = dir.path / "child.log";
    options.env = environment_with({{"DISPLAY", server.display}, {"QT_QPA_PLATFORM", "xcb"}, {kX11ChildVariable, "1"}});
    Process process({fs::read_symlink("/proc/self/exe").string(), "--gtest_also_run_disabled_tests",
                     "--gtest_filter=" + child},
                    options);
    const auto status = process.wait_exit(30s);
    std::ifstream in(dir.path / "child.log");
    log.assign(std::istreambuf_iterator<char>(in), {});
    ASSERT_TRUE(status) << "the child did not finish:\n" << log;
    EXPECT_EQ(*status, 0) << log;
    EXPECT_NE(log.find("[  PASSED  ] 1 test"), std::string::npos) << log;
}

}  // namespace umf::test
