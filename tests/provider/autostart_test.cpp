// The provider's desktop entry (desktop/desktop_entry.hpp) and starting at
// login (desktop/autostart.hpp): the entry's text, the autostart file written
// and removed, and `umf-provider autostart` run for real.
#if defined(UMF_PROVIDER_TESTS)

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <stdexcept>
#include <string>

#include "provider/desktop/autostart.hpp"
#include "provider/desktop/desktop_entry.hpp"
#include "tests/support/process.hpp"
#include "tests/support/temp_dir.hpp"

namespace {

namespace fs = std::filesystem;
using namespace umf::provider;
using umf::test::TempDir;

std::string read_text(const fs::path& file) {
    std::ifstream in(file);
    return {std::istreambuf_iterator<char>(in), {}};
}

bool has_line(const std::string& text, const std::string& line) {
    return ("\n" + text).find("\n" + line + "\n") != std::string::npos;
}

TEST(DesktopEntry, NamesTheProgramItsIconAndKWinsInterface) {
    const std::string entry = provider_desktop_entry("/usr/bin/umf-provider");
    EXPECT_TRUE(entry.starts_with("[Desktop Entry]\n")) << entry;
    EXPECT_TRUE(has_line(entry, "Exec=/usr/bin/umf-provider")) << entry;
    EXPECT_TRUE(has_line(entry, "Type=Application"));
    EXPECT_TRUE(has_line(entry, "Icon=umf-provider"));
    // KWin lets the program take snapshots only through this line.
    EXPECT_TRUE(has_line(entry, "X-KDE-DBUS-Restricted-Interfaces=org.kde.KWin.ScreenShot2"));
    EXPECT_EQ(entry.find('@'), std::string::npos) << "a placeholder was left: " << entry;
}

// The Desktop Entry Specification's quoting: a path with a space is quoted,
// and the value's backslash escape comes on top of the quoting's.
TEST(DesktopEntry, AnExecutableWithReservedCharactersIsQuoted) {
    EXPECT_TRUE(has_line(provider_desktop_entry("/opt/my apps/umf-provider"), "Exec=\"/opt/my apps/umf-provider\""));
    EXPECT_TRUE(has_line(provider_desktop_entry("/opt/100%/umf-provider"), "Exec=/opt/100%%/umf-provider"));
    EXPECT_TRUE(has_line(provider_desktop_entry("/opt/a$b/umf-provider"), "Exec=\"/opt/a\\\\$b/umf-provider\""));
}

TEST(Autostart, OnWritesTheEntryOffRemovesIt) {
    TempDir dir;
    const fs::path entry = dir.path / "config" / "autostart" / kDesktopEntryName;
    EXPECT_FALSE(autostart_enabled(entry));
    set_autostart(entry, true, "/usr/bin/umf-provider");
    EXPECT_TRUE(autostart_enabled(entry));
    EXPECT_EQ(read_text(entry), provider_desktop_entry("/usr/bin/umf-provider"));
    set_autostart(entry, true, "/usr/bin/umf-provider");  // again: the same file
    EXPECT_TRUE(autostart_enabled(entry));
    set_autostart(entry, false, "/usr/bin/umf-provider");
    EXPECT_FALSE(fs::exists(entry));
    set_autostart(entry, false, "/usr/bin/umf-provider");  // already off: fine
    EXPECT_FALSE(autostart_enabled(entry));
}

// A user's copy that hides the entry turns it off, by the specification.
TEST(Autostart, AHiddenEntryIsOff) {
    TempDir dir;
    const fs::path entry = dir.path / kDesktopEntryName;
    std::ofstream(entry) << "[Desktop Entry]\nType=Application\nExec=/usr/bin/umf-provider\nHidden=true\n";
    EXPECT_FALSE(autostart_enabled(entry));
}

TEST(Autostart, AFolderThatCannotBeMadeIsAnErrorNamingIt) {
    TempDir dir;
    std::ofstream(dir.path / "autostart") << "a file where the folder should be";
    const fs::path entry = dir.path / "autostart" / kDesktopEntryName;
    try {
        set_autostart(entry, true, "/usr/bin/umf-provider");
        FAIL() << "no error";
    } catch (const std::runtime_error& e) {
        EXPECT_NE(std::string(e.what()).find((dir.path / "autostart").string()), std::string::npos) << e.what();
    }
    EXPECT_THROW(set_autostart({}, true, "/usr/bin/umf-provider"), std::runtime_error);
}

// The command, as a user runs it: the entry names the program itself.
TEST(Autostart, TheCommandSwitchesItForThisProgram) {
    TempDir dir;
    const std::string tool = std::string("XDG_CONFIG_HOME=") + dir.path.string() + " " + UMF_PROVIDER_TOOL;
    auto result = umf::test::run_command(tool + " autostart 2>&1");
    ASSERT_EQ(result.exit_code, 0) << result.out;
    EXPECT_NE(result.out.find("does not start at login"), std::string::npos) << result.out;

    result = umf::test::run_command(tool + " autostart on 2>&1");
    ASSERT_EQ(result.exit_code, 0) << result.out;
    const fs::path entry = dir.path / "autostart" / kDesktopEntryName;
    EXPECT_NE(result.out.find("starts at login (" + entry.string() + ")"), std::string::npos) << result.out;
    EXPECT_TRUE(has_line(read_text(entry), "Exec=" + fs::canonical(UMF_PROVIDER_TOOL).string())) << read_text(entry);

    result = umf::test::run_command(tool + " autostart off 2>&1");
    ASSERT_EQ(result.exit_code, 0) << result.out;
    EXPECT_FALSE(fs::exists(entry));
    EXPECT_EQ(umf::test::run_command(tool + " autostart maybe 2>&1").exit_code, 2);
    EXPECT_EQ(umf::test::run_command(tool + " autostart on off 2>&1").exit_code, 2);

    std::ofstream(dir.path / "autostart-blocked") << "x";
    result = umf::test::run_command("XDG_CONFIG_HOME=" + (dir.path / "autostart-blocked").string() + " " +
                                    UMF_PROVIDER_TOOL + " autostart on 2>&1");
    EXPECT_EQ(result.exit_code, 3) << result.out;
    EXPECT_NE(result.out.find("autostart-blocked"), std::string::npos) << result.out;
}

}  // namespace

#endif
