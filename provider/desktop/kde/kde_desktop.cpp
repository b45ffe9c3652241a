#include "provider/desktop/kde/kde_desktop.hpp"

#include <sys/stat.h>
#include <unistd.h>

#include <QDBusConnection>
#include <QDBusConnectionInterface>
#include <algorithm>
#include <cstdlib>
#include <iostream>
#include <mutex>

#include "provider/desktop/kde/kde_window_watch.hpp"
#include "provider/desktop/kde/kwin_screenshot.hpp"
#include "provider/desktop/kde/kwin_scripting.hpp"
#include "provider/desktop/kde/kwin_scripts.hpp"
#include "provider/desktop/kde/wayland_outputs.hpp"

namespace umf::provider {

namespace {

namespace fs = std::filesystem;

// A folder only the provider's user may read or write: a script found
// there is run by KWin.
fs::path private_folder(fs::path wanted) {
    if (wanted.empty()) {
        const char* runtime = std::getenv("XDG_RUNTIME_DIR");
        if (!runtime || !*runtime) throw DesktopError("KDE: XDG_RUNTIME_DIR is not set");
        wanted = fs::path(runtime) / ("umf-kwin-" + std::to_string(::getpid()));
    }
    std::error_code ec;
    fs::create_directories(wanted, ec);
    ::chmod(wanted.c_str(), 0700);
    struct stat info {};
    if (::lstat(wanted.c_str(), &info) != 0 || !S_ISDIR(info.st_mode) || info.st_uid != ::getuid() ||
        (info.st_mode & 077) != 0)
        throw DesktopError("KDE: the script folder " + wanted.string() + " is not a private folder of this user");
    return wanted;
}

std::string wayland_display_name(const std::string& wanted) {
    if (!wanted.empty()) return wanted;
    const char* env = std::getenv("WAYLAND_DISPLAY");
    return env ? env : "";
}

class KdeDesktop final : public Desktop {
public:
    explicit KdeDesktop(KdeDesktopOptions options)
        : options_(std::move(options)),
          display_(wayland_display_name(options_.wayland_display)),
          folder_(private_folder(options_.script_dir)),
          bus_(kde_bus_connection(options_.bus_address)) {
        scripting_ = std::make_shared<KWinScripting>(bus_, folder_);
        if (scripting_->kwin_owner().empty())
            throw DesktopError("KWin is not on the session bus (nobody owns org.kde.KWin)");
        const WaylandFacts facts = query_wayland(display_, options_.timeout);
        layer_shell_ = facts.globals.count("zwlr_layer_shell_v1") > 0;
        probe_windows();
        probe_snapshots();
    }
    ~KdeDesktop() override {
        scripting_.reset();
        // The connection is the backend's own (kde_bus_connection): a desktop
        // opened again after KWin restarts makes a new one.
        QDBusConnection::disconnectFromBus(bus_.name());
        std::error_code ec;
        fs::remove_all(folder_, ec);
    }

    std::string name() const override { return "kde"; }

    DesktopAbilities abilities() const override {
        DesktopAbilities a;
        a.windows = windows_;
        a.placement = windows_;
        a.snapshots = snapshots_;
        a.field = layer_shell_ && static_cast<bool>(options_.layer_surface);
        if (!windows_)
            a.notes.push_back("KWin did not run the provider's window script (" + windows_error_ +
                              "): the window under the point and placement are off.");
        if (!snapshots_) a.notes.push_back(snapshots_error_);
        if (!layer_shell_)
            a.notes.push_back("KWin offers no zwlr_layer_shell_v1 (Plasma 5.26 or newer has it), so no field is shown.");
        else if (!options_.layer_surface)
            a.notes.push_back("This build has no layer-shell field surface, so no field is shown.");
        return a;
    }

    std::vector<DesktopOutput> outputs() const override {
        try {
            return query_wayland(display_, options_.timeout).outputs;
        } catch (const DesktopError&) {
            return {};
        }
    }

    std::optional<WindowInfo> window_at(double x, double y, const WindowFilter& filter) const override {
        try {
            const auto windows = parse_window_list(scripting_->run(list_windows_script(), options_.timeout));
            if (!windows) throw DesktopError("KWin's window list could not be read");
            return window_at_point(*windows, x, y, filter, outputs());
        } catch (const DesktopError& e) {
            note_failure(e.what());
            return std::nullopt;  // KWin gone or stuck: the bare desktop, as the seam asks
        }
    }

    Capture capture(const WindowRect& rect) const override {
        const WindowRect all = screen();
        if (all.empty()) throw DesktopError("KWin's outputs cannot be read (is KWin still running?)");
        const int left = std::max(rect.x, all.x), top = std::max(rect.y, all.y);
        const int right = std::min(rect.x + rect.width, all.x + all.width);
        const int bottom = std::min(rect.y + rect.height, all.y + all.height);
        if (right <= left || bottom <= top) return {};
        std::lock_guard lock(capture_mutex_);
        return kwin_capture_area(bus_, {left, top, right - left, bottom - top}, options_.timeout);
    }

    std::unique_ptr<NewWindowWatch> watch_new_window(const WindowPlacement& where) const override {
        if (!windows_) return nullptr;
        try {
            return std::make_unique<KdeWindowWatch>(scripting_, where, options_.timeout);
        } catch (const DesktopError&) {
            return nullptr;
        }
    }

    std::unique_ptr<FieldSurface> make_field_surface(QScreen* screen, ScreenField field,
                                                     const std::vector<std::string>& palette) override {
        if (!layer_shell_ || !options_.layer_surface) return nullptr;
        return options_.layer_surface(display_, screen, std::move(field), palette);
    }

private:
    // Said on the console once per new failure, not once per aim.
    void note_failure(const std::string& what) const {
        std::lock_guard lock(note_mutex_);
        if (what == last_failure_) return;
        last_failure_ = what;
        std::cerr << "desktop: kde: no window under the point: " << what << std::endl;
    }

    void probe_windows() {
        try {
            windows_ = parse_window_list(scripting_->run(list_windows_script(), options_.timeout)).has_value();
            if (!windows_) windows_error_ = "its answer could not be read";
        } catch (const DesktopError& e) {
            windows_error_ = e.what();
        }
    }

    // A 1x1 capture tells both whether the interface is there and whether
    // KWin lets this executable use it.
    void probe_snapshots() {
        const auto owner = bus_.interface()->serviceOwner("org.kde.KWin.ScreenShot2");
        if (!owner.isValid() || owner.value().isEmpty()) {
            snapshots_error_ =
                "KWin offers no screenshot interface (org.kde.KWin.ScreenShot2; in KWin 5.27 its screenshot effect "
                "runs only with OpenGL compositing), so snapshots are off.";
            return;
        }
        try {
            kwin_capture_area(bus_, {0, 0, 1, 1}, options_.timeout);
            snapshots_ = true;
        } catch (const DesktopError& e) {
            snapshots_error_ = std::string(e.what()) + ", so snapshots are off.";
        }
    }

    KdeDesktopOptions options_;
    std::string display_;
    fs::path folder_;
    mutable QDBusConnection bus_;
    std::shared_ptr<KWinScripting> scripting_;
    bool layer_shell_ = false;
    bool windows_ = false;
    bool snapshots_ = false;
    std::string windows_error_;
    std::string snapshots_error_;
    mutable std::mutex capture_mutex_;
    mutable std::mutex note_mutex_;
    mutable std::string last_failure_;
};

}  // namespace

std::unique_ptr<Desktop> make_kde_desktop(KdeDesktopOptions options) {
    return std::make_unique<KdeDesktop>(std::move(options));
}

}  // namespace umf::provider
