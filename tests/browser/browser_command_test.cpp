// `umf-provider browser install` and `browser status` as a person runs them:
// the manifests written where each browser looks, the running provider's
// browsers listed over its control socket, and clear errors otherwise.
#ifdef UMF_PROVIDER_TESTS
#include <gtest/gtest.h>
#include <sys/stat.h>

#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>

#include "provider/browser/browser_link.hpp"
#include "provider/commands/browser_command.hpp"
#include "provider/service/control_socket.hpp"
#include "tests/support/scoped_env.hpp"
#include "tests/support/temp_dir.hpp"

namespace umf::provider {
namespace {

using json = nlohmann::json;
using umf::cli::UsageError;
using umf::test::ScopedEnv;
using umf::test::TempDir;
constexpr unsigned short kPort = 47994;

struct Outcome {
    int code;
    std::string out, err;
};

Outcome browser(std::vector<std::string> words, std::map<std::string, std::string> named = {},
                std::vector<std::string> flags = {}) {
    cli::Args a;
    a.positional = std::move(words);
    for (auto& [k, v] : named) a.named[k] = v;
    a.flags = std::move(flags);
    std::ostringstream out, err;
    const int code = run_browser(a, out, err);
    return {code, out.str(), err.str()};
}

std::string read(const std::filesystem::path& p) {
    std::ifstream in(p);
    return std::string(std::istreambuf_iterator<char>(in), {});
}

TEST(BrowserCommand, InstallWritesEveryBrowsersManifestNamingTheHost) {
    TempDir home;
    ScopedEnv h("HOME", home.path.string());
    ScopedEnv c("XDG_CONFIG_HOME", (home.path / "cfg").string());
    const Outcome o = browser({"install"}, {{"host", UMF_BROWSER_HOST_TOOL}});
    ASSERT_EQ(o.code, 0) << o.err;
    for (const auto& file : {home.path / "cfg/chromium/NativeMessagingHosts/org.umf.browser.json",
                             home.path / "cfg/google-chrome/NativeMessagingHosts/org.umf.browser.json",
                             home.path / "cfg/microsoft-edge/NativeMessagingHosts/org.umf.browser.json",
                             home.path / ".mozilla/native-messaging-hosts/org.umf.browser.json"}) {
        const json manifest = json::parse(read(file));
        EXPECT_EQ(manifest["path"], UMF_BROWSER_HOST_TOOL) << file;
        EXPECT_NE(o.out.find(file.string()), std::string::npos) << o.out;
    }
    EXPECT_NE(o.out.find("chrome://extensions"), std::string::npos) << o.out;
    EXPECT_NE(o.out.find(std::string(UMF_BROWSER_EXTENSION_DIR)), std::string::npos) << o.out;
    // System places under a prefix, and a host that is not there.
    ASSERT_EQ(browser({"install"}, {{"host", UMF_BROWSER_HOST_TOOL}, {"prefix", (home.path / "root").string()}}, {"system"})
                  .code,
              0);
    EXPECT_TRUE(std::filesystem::exists(home.path / "root/etc/chromium/native-messaging-hosts/org.umf.browser.json"));
    const Outcome missing = browser({"install"}, {{"host", (home.path / "nothing").string()}});
    EXPECT_EQ(missing.code, 3);
    EXPECT_NE(missing.err.find("no umf-browser-host at"), std::string::npos) << missing.err;
}

TEST(BrowserCommand, StatusAsksTheRunningProvider) {
    TempDir runtime;
    ScopedEnv env("XDG_RUNTIME_DIR", runtime.path.string());
    const Outcome nobody = browser({"status"}, {{"port", std::to_string(kPort)}});
    EXPECT_EQ(nobody.code, 4);
    EXPECT_NE(nobody.err.find("no provider is running at"), std::string::npos) << nobody.err;
    {
        // A provider that looks into no browsers (public or headless).
        ControlSocket socket(control_socket_path(kPort), std::make_shared<SharedItems>());
        const Outcome none = browser({"status"}, {{"port", std::to_string(kPort)}});
        EXPECT_EQ(none.code, 3);
        EXPECT_NE(none.err.find("does not look into browsers"), std::string::npos) << none.err;
    }
    auto link = std::make_shared<BrowserLink>();
    link->listen(browser_socket_path(kPort));
    ControlSocket socket(control_socket_path(kPort), std::make_shared<SharedItems>(), nullptr, link);
    const Outcome empty = browser({"status"}, {{"port", std::to_string(kPort)}});
    EXPECT_EQ(empty.code, 0) << empty.err;
    EXPECT_NE(empty.out.find("no browser is connected"), std::string::npos) << empty.out;
    const Outcome as_json = browser({"status"}, {{"port", std::to_string(kPort)}}, {"json"});
    EXPECT_EQ(json::parse(as_json.out)["browsers"], json::array());
}

TEST(BrowserCommand, WrongUsage) {
    EXPECT_THROW(browser({}), UsageError);
    EXPECT_THROW(browser({"launch"}), UsageError);
    EXPECT_THROW(browser({"install", "status"}), UsageError);
    EXPECT_THROW(browser({"install"}, {{"port", "1"}}), UsageError);
    EXPECT_THROW(browser({"install"}, {{"prefix", "/tmp"}}), UsageError);
    EXPECT_THROW(browser({"status"}, {}, {"system"}), UsageError);
    EXPECT_THROW(browser({"status"}, {{"host", "/x"}}), UsageError);
}

}  // namespace
}  // namespace umf::provider
#endif
