// Commands that talk to a running provider (`puts`, `share`, `browser
// status`, `pair`) without --port: they find the one provider of this user
// that runs, over real control sockets in a temporary XDG_RUNTIME_DIR; the
// console's hints name a port that is not the default; a client that leaves
// before its answer does not end the provider.
#if defined(UMF_PROVIDER_TESTS)

#include <gtest/gtest.h>

#include <sys/socket.h>
#include <sys/un.h>
#include <unistd.h>

#include <cstring>
#include <sstream>

#include "provider/commands/common_options.hpp"
#include "provider/commands/control_client.hpp"
#include "provider/commands/pair_command.hpp"
#include "provider/content/shared_items.hpp"
#include "provider/put/put_deciders.hpp"
#include "provider/service/control_socket.hpp"
#include "shared/cli/args.hpp"
#include "shared/io/runtime_dir.hpp"
#include "tests/support/scoped_env.hpp"
#include "tests/support/temp_dir.hpp"

namespace {

using namespace umf::provider;
using umf::test::ScopedEnv;
using umf::test::TempDir;

// A socket connected to `path`, or -1.
int connect_to(const std::filesystem::path& path) {
    sockaddr_un addr{};
    addr.sun_family = AF_UNIX;
    std::strncpy(addr.sun_path, path.c_str(), sizeof addr.sun_path - 1);
    const int fd = ::socket(AF_UNIX, SOCK_STREAM, 0);
    if (::connect(fd, reinterpret_cast<const sockaddr*>(&addr), sizeof addr) != 0) {
        ::close(fd);
        return -1;
    }
    return fd;
}

std::shared_ptr<ControlSocket> provider_on(unsigned short port) {
    return std::make_shared<ControlSocket>(umf::control_socket_path(port), std::make_shared<SharedItems>(),
                                           std::make_shared<ControlPutDecider>());
}

TEST(RunningProvider, ControlSocketNamesGiveTheirPorts) {
    EXPECT_EQ(umf::provider_socket_port("provider-47470.sock"), 47470);
    EXPECT_EQ(umf::provider_socket_port("provider-1.sock"), 1);
    for (const char* name : {"provider-.sock", "provider-65536.sock", "provider-123456.sock", "provider-12a.sock",
                             "browser-47470.sock", "provider-47470.sock.old", "provider-47470"})
        EXPECT_FALSE(umf::provider_socket_port(name).has_value()) << name;
    EXPECT_TRUE(umf::is_browser_socket_name("browser-47470.sock"));
    EXPECT_FALSE(umf::is_browser_socket_name("browser-99999.sock"));
}

TEST(RunningProvider, CommandsWithoutPortFindTheOneProviderThatRuns) {
    TempDir runtime;
    ScopedEnv env("XDG_RUNTIME_DIR", runtime.path.string());
    umf::cli::Args no_port;
    std::ostringstream out, err;

    // None runs: the default port, and the request says so.
    EXPECT_TRUE(running_provider_ports().empty());
    EXPECT_FALSE(running_provider_port(no_port).has_value());
    EXPECT_EQ(run_puts(no_port, out, err), kServeError);
    EXPECT_NE(err.str().find("no provider is running"), std::string::npos) << err.str();

    // One runs on another port (and a socket file a killed one left behind).
    const auto first = provider_on(47123);
    {
        const std::filesystem::path stale = umf::control_socket_path(47200);
        sockaddr_un addr{};
        addr.sun_family = AF_UNIX;
        std::strncpy(addr.sun_path, stale.c_str(), sizeof addr.sun_path - 1);
        const int fd = ::socket(AF_UNIX, SOCK_STREAM, 0);
        ASSERT_EQ(::bind(fd, reinterpret_cast<const sockaddr*>(&addr), sizeof addr), 0);
        ::close(fd);  // the file stays; nobody listens
    }
    EXPECT_EQ(running_provider_ports(), std::vector<unsigned short>{47123});
    EXPECT_EQ(running_provider_port(no_port), std::optional<unsigned short>(47123));
    out.str("");
    err.str("");
    EXPECT_EQ(run_puts(no_port, out, err), kOk) << err.str();
    EXPECT_EQ(out.str(), "no puts are waiting for an answer\n");

    // Two run: the command cannot guess, and says which ports to choose from.
    const auto second = provider_on(47124);
    try {
        running_provider_port(no_port);
        ADD_FAILURE() << "no UsageError with two providers";
    } catch (const umf::cli::UsageError& e) {
        EXPECT_NE(std::string(e.what()).find("ports 47123 and 47124"), std::string::npos) << e.what();
    }
    umf::cli::Args given;
    given.named["port"] = "47124";
    EXPECT_EQ(running_provider_port(given), std::optional<unsigned short>(47124));
}

// `pair --rotate` asks a running provider to read its pairing and field
// again (tests/screens/two_screens_test.sh runs the whole): its answer, and
// why not.
TEST(RunningProvider, RotatedIsReadAgainWhereTheProviderCan) {
    SharedItems items;
    EXPECT_NE(handle_control_request(R"({"cmd":"rotated"})", &items, nullptr).find("at its start only"),
              std::string::npos);
    const ReadRotated read = [] { return RotatedRead{"/home/u/.config/umf", {"b4-64x36-00000000000000a1", true}}; };
    EXPECT_EQ(handle_control_request(R"({"cmd":"rotated"})", &items, nullptr, nullptr, &read),
              R"({"config_dir":"/home/u/.config/umf","field":"b4-64x36-00000000000000a1","field_changed":true,"ok":true})");
    const ReadRotated failing = []() -> RotatedRead { throw std::runtime_error("cannot read field-seed"); };
    const std::string refused = handle_control_request(R"({"cmd":"rotated"})", nullptr, nullptr, nullptr, &failing);
    EXPECT_NE(refused.find(R"("ok":false)"), std::string::npos) << refused;
    EXPECT_NE(refused.find("cannot read field-seed"), std::string::npos) << refused;
}

TEST(RunningProvider, HintsNameThePortWhenItIsNotTheDefault) {
    EXPECT_EQ(with_port("umf-provider puts", kDefaultPort), "umf-provider puts");
    EXPECT_EQ(with_port("umf-provider puts", 47471), "umf-provider puts --port 47471");
}

// Without MSG_NOSIGNAL the provider's answer to a client that has closed
// raises SIGPIPE, whose default action ends the process (this test's).
TEST(RunningProvider, AClientGoneBeforeItsAnswerDoesNotEndTheProvider) {
    TempDir runtime;
    ScopedEnv env("XDG_RUNTIME_DIR", runtime.path.string());
    const auto provider = provider_on(47125);
    const std::string request = "{\"cmd\":\"list\"}\n";
    for (int i = 0; i < 300; ++i) {
        const int fd = connect_to(provider->path());
        ASSERT_GE(fd, 0);
        ASSERT_EQ(::write(fd, request.data(), request.size()), static_cast<ssize_t>(request.size()));
        ::close(fd);
    }
    EXPECT_EQ(control_request(provider->path(), R"({"cmd":"ping"})"), R"({"ok":true})");
}

}  // namespace

#endif
