#include "provider/desktop/autostart.hpp"

#include <cstdlib>
#include <fstream>
#include <ostream>
#include <stdexcept>
#include <system_error>

#include "provider/common/install_paths.hpp"
#include "provider/desktop/desktop_entry.hpp"
#include "shared/io/atomic_file.hpp"

namespace umf::provider {

namespace fs = std::filesystem;

fs::path autostart_entry_path() {
    if (const char* xdg = std::getenv("XDG_CONFIG_HOME"); xdg && *xdg) return fs::path(xdg) / "autostart" / kDesktopEntryName;
    if (const char* home = std::getenv("HOME"); home && *home)
        return fs::path(home) / ".config" / "autostart" / kDesktopEntryName;
    return {};
}

bool autostart_enabled(const fs::path& entry) {
    std::ifstream in(entry);
    if (!in) return false;
    for (std::string line; std::getline(in, line);)
        if (line == "Hidden=true") return false;
    return true;
}

void set_autostart(const fs::path& entry, bool on, const fs::path& executable) {
    if (entry.empty()) throw std::runtime_error("neither XDG_CONFIG_HOME nor HOME is set, so there is no autostart folder");
    std::error_code ec;
    if (!on) {
        fs::remove(entry, ec);
        if (ec) throw std::runtime_error("cannot remove " + entry.string() + ": " + ec.message());
        return;
    }
    fs::create_directories(entry.parent_path(), ec);
    if (ec) throw std::runtime_error("cannot make " + entry.parent_path().string() + ": " + ec.message());
    umf::write_file_atomically(entry.string(), provider_desktop_entry(executable.string()));
}

void set_autostart_for_this_program(const fs::path& entry, bool on) {
    const fs::path self = program_path();
    if (self.empty()) throw std::runtime_error("cannot tell where this program is");
    set_autostart(entry, on, self);
}

int run_autostart(std::optional<bool> on, std::ostream& out, std::ostream& err) {
    const fs::path entry = autostart_entry_path();
    if (on) {
        try {
            set_autostart_for_this_program(entry, *on);
        } catch (const std::exception& e) {
            err << "umf-provider: " << e.what() << "\n";
            return 3;
        }
    }
    if (autostart_enabled(entry))
        out << "umf-provider starts at login (" << entry.string() << ")\n";
    else
        out << "umf-provider does not start at login (no " << (entry.empty() ? kDesktopEntryName : entry.string())
            << ")\n";
    return 0;
}

}  // namespace umf::provider
