#include "provider/desktop/gnome/gnome_install.hpp"

#include <QProcess>
#include <QStringList>
#include <cstdlib>
#include <fstream>
#include <optional>
#include <ostream>
#include <stdexcept>

namespace umf::provider {

namespace {

struct Ran {
    bool ok = false;
    std::string out;
};

// A short command's output; never waits more than five seconds.
Ran run(const QString& program, const QStringList& args) {
    QProcess process;
    process.start(program, args);
    if (!process.waitForStarted(5000)) return {};
    if (!process.waitForFinished(5000)) {
        process.kill();
        process.waitForFinished(1000);
        return {};
    }
    const bool ok = process.exitStatus() == QProcess::NormalExit && process.exitCode() == 0;
    return {ok, process.readAllStandardOutput().trimmed().toStdString()};
}

}  // namespace

std::filesystem::path gnome_user_extensions_folder() {
    if (const char* xdg = std::getenv("XDG_DATA_HOME"); xdg && *xdg)
        return std::filesystem::path(xdg) / "gnome-shell/extensions";
    if (const char* home = std::getenv("HOME"); home && *home)
        return std::filesystem::path(home) / ".local/share/gnome-shell/extensions";
    return {};
}

std::filesystem::path install_gnome_extension(const std::filesystem::path& extensions_folder, GnomeExtensionForm form) {
    const auto folder = extensions_folder / std::string(kGnomeExtensionUuid);
    std::filesystem::create_directories(folder);
    for (const auto& file : gnome_extension_files(form)) {
        const auto path = folder / std::string(file.name);
        std::ofstream stream(path, std::ios::binary | std::ios::trunc);
        stream.write(file.text.data(), static_cast<std::streamsize>(file.text.size()));
        if (!stream.flush()) throw std::runtime_error("cannot write " + path.string());
    }
    return folder;
}

std::string with_extension_enabled(const std::string& gvariant_list, const std::string& uuid) {
    const std::string quoted = "'" + uuid + "'";
    if (gvariant_list.find(quoted) != std::string::npos) return gvariant_list;
    const auto open = gvariant_list.find('[');
    const auto close = gvariant_list.rfind(']');
    if (open == std::string::npos || close == std::string::npos || close < open) return "[" + quoted + "]";
    const std::string inside = gvariant_list.substr(open + 1, close - open - 1);
    const bool empty = inside.find_first_not_of(" \t") == std::string::npos;
    return "[" + inside + (empty ? "" : ", ") + quoted + "]";
}

int run_gnome_install(std::ostream& out, std::ostream& err) {
    const std::string uuid(kGnomeExtensionUuid);
    const Ran version = run("gnome-shell", {"--version"});
    const auto major = version.ok ? gnome_shell_major(version.out) : std::nullopt;
    if (!major) {
        err << "umf-provider: cannot tell GNOME Shell's version (gnome-shell --version"
            << (version.out.empty() ? " failed" : " said: " + version.out) << "); is GNOME Shell installed?\n";
        return 1;
    }
    const auto form = gnome_extension_form_for(*major);
    if (!form) {
        err << "umf-provider: GNOME Shell " << *major << " is too old; the umf extension needs 43 or later\n";
        return 1;
    }
    const auto extensions = gnome_user_extensions_folder();
    if (extensions.empty()) {
        err << "umf-provider: neither XDG_DATA_HOME nor HOME is set: nowhere to install the extension\n";
        return 1;
    }
    std::filesystem::path folder;
    try {
        folder = install_gnome_extension(extensions, *form);
    } catch (const std::exception& e) {
        err << "umf-provider: " << e.what() << "\n";
        return 1;
    }
    out << "Installed the umf GNOME Shell extension (" << (*form == GnomeExtensionForm::legacy ? "GNOME 43-44" : "GNOME 45+")
        << " form, for GNOME Shell " << version.out.substr(version.out.rfind(' ') + 1) << ") in " << folder.string() << "\n";

    // The running shell knows only the extensions it found at login, so
    // `gnome-extensions enable` may refuse a new one: the key then does it.
    bool enabled = run("gnome-extensions", {"enable", QString::fromStdString(uuid)}).ok;
    if (!enabled) {
        const Ran list = run("gsettings", {"get", "org.gnome.shell", "enabled-extensions"});
        if (list.ok) {
            const std::string wanted = with_extension_enabled(list.out, uuid);
            enabled = wanted == list.out ||
                      run("gsettings", {"set", "org.gnome.shell", "enabled-extensions", QString::fromStdString(wanted)}).ok;
        }
    }
    if (!enabled) {
        err << "umf-provider: could not enable it: run  gnome-extensions enable " << uuid << "  after logging in again\n";
        return 1;
    }
    out << "Enabled " << uuid << ".\n";
    if (run("gsettings", {"get", "org.gnome.shell", "disable-user-extensions"}).out == "true")
        out << "Extensions are switched off for this user: run  gsettings set org.gnome.shell disable-user-extensions false\n";
    out << "Log out and in again: GNOME Shell on Wayland loads new or updated extensions only at login.\n";
    return 0;
}

}  // namespace umf::provider
