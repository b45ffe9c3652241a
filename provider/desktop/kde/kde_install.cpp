#include "provider/desktop/kde/kde_install.hpp"

#include <cstdlib>
#include <ostream>
#include <system_error>

#include "provider/common/install_paths.hpp"
#include "provider/desktop/desktop_entry.hpp"
#include "shared/io/atomic_file.hpp"

namespace umf::provider {

namespace fs = std::filesystem;

int install_kde_desktop_entry(const fs::path& executable, const fs::path& applications, std::ostream& out,
                              std::ostream& err) {
    std::error_code ec;
    fs::create_directories(applications, ec);
    const fs::path file = applications / kDesktopEntryName;
    try {
        umf::write_file_atomically(file.string(), provider_desktop_entry(executable.string()));
    } catch (const std::exception& e) {
        err << "umf-provider: cannot write " << file.string() << ": " << e.what() << "\n";
        return 3;
    }
    out << "wrote " << file.string() << ": KWin now lets " << executable.string()
        << " take snapshots (the window under the point, when it has no document).\n"
           "Install again when the program moves.\n";
    return 0;
}

int run_kde_install(std::ostream& out, std::ostream& err) {
    const fs::path self = program_path();
    if (self.empty()) {
        err << "umf-provider: cannot tell where this program is\n";
        return 3;
    }
    fs::path data;
    if (const char* xdg = std::getenv("XDG_DATA_HOME"); xdg && *xdg) data = xdg;
    else if (const char* home = std::getenv("HOME"); home && *home) data = fs::path(home) / ".local" / "share";
    else {
        err << "umf-provider: neither XDG_DATA_HOME nor HOME is set\n";
        return 3;
    }
    return install_kde_desktop_entry(self, data / "applications", out, err);
}

}  // namespace umf::provider
