// The provider's command line: the command word's dispatch to commands/
// (serve when none is given), and what serving needs before Qt starts.
#include "provider/command_line.hpp"

#include <pthread.h>
#include <signal.h>
#include <unistd.h>

#include <QApplication>
#include <cstdlib>
#include <cstring>
#include <iostream>
#include <optional>
#include <string>
#include <variant>
#include <vector>

#include "provider/commands/browser_command.hpp"
#include "provider/commands/common_options.hpp"
#include "provider/commands/compose_command.hpp"
#include "provider/commands/desktop_keeper.hpp"
#include "provider/commands/pair_command.hpp"
#include "provider/commands/preset_options.hpp"
#include "provider/commands/serve_command.hpp"
#include "provider/commands/trust_command.hpp"
#include "provider/common/install_paths.hpp"
#include "provider/common/config_dir.hpp"
#include "provider/desktop/desktop_choice.hpp"
#include "provider/desktop/display_socket.hpp"
#include "provider/desktop/autostart.hpp"
#include "provider/desktop/gnome/gnome_install.hpp"
#include "provider/desktop/kde/kde_install.hpp"
#include "provider/screen/gui_application.hpp"
#include "provider/service/control_socket.hpp"
#include "provider/tuning/desktop_controls.hpp"
#include "shared/cli/args.hpp"

namespace umf::provider {

const char* const kProviderUsage = R"(umf-provider: show a marker field and serve what it points at

usage:
  umf-provider [serve] [--board BOARD.json] [--preset NAME] [--port P] [--headless]
               [--screen WxH] [--public] [--bind ADDR] [--host HOST] [--web DIR]
               [--config-dir DIR] [--no-qr] [--no-overlay] [--tune] [--no-announce] [--shipped-field]
               [--desktop x11|wlroots|kde|gnome|none]
               [--puts ask|always|never] [--put-dir DIR] [--put-max-mb N]
  umf-provider pair [--port P] [--host HOST] [--config-dir DIR] [--rotate [--root] [--field]] [--no-qr]
  umf-provider trust [--config-dir DIR] [--port P] [--host HOST]
  umf-provider trust export FILE [--der | --mobileconfig] [--config-dir DIR]
  umf-provider share FILE|URL --rect X,Y,W,H [--title T] [--screen N] [--port P]
  umf-provider share --list | --remove ID [--port P]
  umf-provider puts [--json] [--port P]
  umf-provider puts --accept ID [--open] [--always] | --dismiss ID [--port P]
  umf-provider browser install [--system [--prefix DIR]] [--host PATH]
  umf-provider browser status [--json] [--port P]
  umf-provider autostart [on|off]
  umf-provider gnome install
  umf-provider kde install
  umf-provider compose (--content SCREEN.png | --board BOARD.json | both) --preset NAME
                       --time T --out OUT.png --map MAP.json [--screen WxH] [--config-dir DIR]
                       [--shipped-field]
                       [preset settings, as for serve: --module-px P --blur B ...]
  umf-provider --version [--verbose]
  umf-provider --help

serve    (the default) listens for requesters on https://ADDR:P (WebSocket at /ws;
         default every address, --bind 127.0.0.1 keeps it to this machine;
         port 47470, port 0 picks a free one), prints the
         pairing URL and its QR code, and serves until SIGINT or SIGTERM.
         Without a display, or with --headless, the screen is virtual (--screen,
         default 1920x1080) and shows BOARD.json, or the built-in demo board.
         On a desktop with --board the board fills the screen; without one the
         field is mixed over every screen (--no-overlay leaves it out) and
         pointing takes the window there. The desktop backend comes from the
         session (X11; on Wayland: Sway/Hyprland/river, KDE Plasma, GNOME);
         --desktop names it instead, and the console says which one runs and
         what does not work there. A Wayland compositor without a backend gets
         no field at all, and boards, shares and puts work as everywhere.
         The tray icon switches the overlay and its preset and opens the
         tuning window (--tune opens it at start) and the pairing QR code.
         --public (kiosks) welcomes any requester and serves board items only.
         Where Avahi runs, the provider announces itself on the local network
         (DNS-SD, _umf._tcp, with its HOST.local name and the fingerprint of
         its root, never the token); --no-announce, or --bind 127.0.0.1,
         leaves that out. The field is this screen's own, made from a seed
         kept in the configuration directory (field-seed), so that a phone
         paired with another screen in the room never takes a point from
         it and says it sees another screen; --shipped-field shows the field
         every screen shows instead (printed fields made from it before).
pair     prints the pairing URL and its QR code; --rotate makes a new token
         first, which unpairs every requester (a running provider of the
         same configuration takes it at once; connections it welcomed
         before stay until they end); --rotate --root also makes a new
         screen root, so every requester pairs again and phones that trusted
         the old root should remove it (a running provider serves the old
         root until it restarts); --rotate --field also makes a new seed for
         the screen's own field, which a running provider shows at once.
trust    prints the fingerprint of the screen's root, the certificate
         authority (made on first start, kept in the configuration directory)
         that issues the certificate the provider serves, and where phones
         get it; a phone or browser that trusts it opens the page without a
         warning. It may vouch only for .local names, localhost and private,
         link-local and loopback addresses. export writes it to FILE (- for
         standard output): PEM, DER with --der (Android's .crt), or an Apple
         configuration profile with --mobileconfig (iOS).
share    pins a file or URL to a region of the running provider's screen, so
         pointing there takes it; --list and --remove ID manage what is shared.
puts     lists the puts (a phone giving the screen a URL or a file) waiting for
         an answer at the running provider, or answers one: --accept ID saves
         the file in the put folder (a URL: opens it), --open also opens the
         file, --always accepts that phone's puts from now on without asking;
         --dismiss ID refuses it. --json prints the list as JSON.
browser  install sets up the browser companion, so that pointing at a Chromium,
         Chrome, Edge or Firefox window takes its page (not a picture of it):
         it writes the native-messaging host manifests (per user; --system:
         /etc/... and /usr/lib/mozilla/... under --prefix, default /) naming
         umf-browser-host (beside this program, or --host PATH) and says how
         to load the extension. status lists the browsers connected to the
         running provider and the page each window shows (private windows
         are never reported).
autostart on starts the provider (as `umf-provider`, with the overlay) at each
         login to this desktop, as the tray's "Start at login" does; off stops
         that; alone, says which. (For a screen without a desktop session, a
         kiosk, the systemd user unit does it: systemctl --user enable --now
         umf-provider.)
gnome    install installs and enables the umf GNOME Shell extension, which
         shows the field and answers the provider on GNOME (Wayland); GNOME
         loads it at the next login.
kde      install lets KWin (KDE Plasma) answer the provider's snapshots: it
         writes umf-provider.desktop for this program into
         ~/.local/share/applications, which KWin's screenshot interface asks
         for (the menu entry an installed package brings does the same for
         /usr/bin/umf-provider).
compose  writes the screen exactly as shown at time T (content, the board over
         it, the field at the preset's opacity then) and the map from field to
         screen pixels.
--version prints the version; --verbose adds where this program takes its
         fields, phone page and browser extension from (PREFIX/share/umf when
         installed).

--preset      overlay preset: subtle, balanced, visible, static, kiosk,
              invisible (a pulse of a few grey levels that phones find over
              their frames), or one of yours in CONFIG_DIR/presets.json
              (default: kiosk with a board, else balanced).
--opacity-min A --opacity-max A --period S --waveform sine|triangle --module-px P
--blur B --region full|focus --focus-radius M --activation always|on_demand
--fade S --palette #rrggbb,#rrggbb
              change the preset's settings for this run (see the tuning
              window to keep them).
--port        serve: the port to listen on. pair, share, puts, browser status:
              the running provider's port; without it the one provider of
              yours that runs (name one when several run), else 47470.
--config-dir  where the screen's root, the certificate it issued and the pairing token are kept
              (default $XDG_CONFIG_HOME/umf, else ~/.config/umf); made on first use.
--host        the host name or address put in the pairing URL (default: the
              bind address, or this machine's first non-loopback IPv4 address
              when binding to all addresses).
--puts        what happens to puts (a phone giving this screen a URL or a file at
              the place it points): ask (the default: a prompt there on a desktop,
              and `umf-provider puts`), always (accepted without asking), never.
              --public takes no puts unless --puts is given.
--put-dir     where accepted files are saved (default: the XDG download folder,
              else ~/Downloads).
--put-max-mb  the largest file a put may bring, in megabytes (default 4295, 4 GiB);
              larger ones, and any beyond the folder's free space, are refused
              with too_large before anyone is asked.
--web         serve the web client from DIR (default: the phone page this build
              made, else a page saying how to pair). Phones use it over the
              WebSocket at /ws, or over HTTPS requests under /api/ where the
              browser refuses the WebSocket (docs/PROTOCOL.md).

exit codes: 0 success; 2 wrong usage; 3 the configuration directory, TLS
            identity, token, board or an input could not be read or written;
            4 the server could not start, or (share, puts, browser status) no
            provider is running.
)";

namespace {



// The tray and tuning window as the serve command knows its controls.
class TrayControls final : public DesktopControls, public ProviderControls {
public:
    using DesktopControls::DesktopControls;
    void set_status(const std::string& status) override { DesktopControls::set_status(status); }
};

// On a desktop the provider runs under a keeper that outlives the display
// (commands/desktop_keeper.hpp). In the keeper, once it is done: its exit
// code. In the provider it starts (or with no desktop at all): nullopt, with
// the role in `hooks` and the port, the desktop and `headless` as it says.
std::optional<int> serve_under_keeper(umf::cli::Args& args, bool& headless, ServeHooks& hooks) {
    if (headless || umf::cli::get(args, "desktop").value_or("") == "none") return std::nullopt;
    const DesktopFacts session = desktop_facts_from_environment();
    if (session.wayland_display.empty() && session.x_display.empty()) return std::nullopt;
    const char* runtime = std::getenv("XDG_RUNTIME_DIR");
    KeeperSettings keeper;
    keeper.shares_file = umf::runtime_dir() / ("shared-items-" + std::to_string(::getpid()) + ".json");
    keeper.display_answers = [session, runtime = std::string(runtime ? runtime : "")] {
        return displays_answer(session, runtime);
    };
    auto role = keep_provider(keeper, std::cerr);
    if (const int* code = std::get_if<int>(&role)) return *code;
    hooks.keeper = std::get<KeeperRole>(role);
    if (hooks.keeper->port) args.named["port"] = std::to_string(*hooks.keeper->port);
    if (!hooks.keeper->with_desktop) {
        // Whatever platform the desktop's Qt was told to use, this one has no display.
        args.named["desktop"] = "none";
        headless = true;
        ::setenv("QT_QPA_PLATFORM", "offscreen", 1);
    }
    return std::nullopt;
}

std::vector<std::string> names(const char* const* list) {
    std::vector<std::string> out;
    for (; *list; ++list) out.emplace_back(*list);
    return out;
}

// Without XDG_RUNTIME_DIR (a server started over ssh, a container) Qt warns
// on every start that it falls back to /tmp/runtime-USER. The provider's
// own sockets go to /tmp/umf-UID then (io/runtime_dir.hpp) and Qt's
// fallback does no harm, so that one warning is left out; every other
// message is printed as Qt would.
void print_qt_message(QtMsgType type, const QMessageLogContext& context, const QString& message) {
    if (message.startsWith(QLatin1String("QStandardPaths: XDG_RUNTIME_DIR not set"))) return;
    std::cerr << qFormatLogMessage(type, context, message).toStdString() << std::endl;
}

}  // namespace

int run_command_line(int argc, char** argv) {
    qInstallMessageHandler(print_qt_message);
    // The command word is optional: `umf-provider --board B` serves.
    if (argc >= 2 && std::strcmp(argv[1], "--version") == 0) {
        const auto args = parse_command_args(argc, argv, 2, {}, {"verbose"});
        std::cout << "umf-provider " << UMF_VERSION << "\n";
        if (umf::cli::has_flag(args, "verbose")) std::cout << install_paths_report();
        return kOk;
    }
    std::string command = "serve";
    int first = 1;
    if (argc >= 2 && std::strncmp(argv[1], "--", 2) != 0) {
        command = argv[1];
        first = 2;
    }
    if (command == "serve") {
        auto args = parse_command_args(argc, argv, first, names(kServeOptions), names(kServeFlags));
        bool headless = umf::cli::has_flag(args, "headless");
        // SIGINT and SIGTERM are taken by run_serve with sigwait: blocked
        // before Qt starts threads of its own (the xcb event reader), which
        // would otherwise receive them and die with the default action.
        sigset_t signals;
        sigemptyset(&signals);
        sigaddset(&signals, SIGINT);
        sigaddset(&signals, SIGTERM);
        pthread_sigmask(SIG_BLOCK, &signals, nullptr);
        ServeHooks hooks;
        if (const auto keeper_done = serve_under_keeper(args, headless, hooks)) return *keeper_done;
        // On a desktop the tray and the tuning window need Qt Widgets.
        auto app = make_gui_application(argc, argv, headless);
        if (!headless && QGuiApplication::platformName() != "offscreen") {
            app.reset();
            app = std::make_unique<QApplication>(argc, argv);
            QApplication::setQuitOnLastWindowClosed(false);
            // Wayland compositors and task bars find the menu entry, and its
            // icon, by this name (the window's app id).
            QGuiApplication::setDesktopFileName("umf-provider");
        }
        if (qobject_cast<QApplication*>(app.get()))
            hooks.desktop_controls = [](OverlayManager* overlay, const std::string& status,
                                        const std::string& presets_file, const std::string& pairing_url,
                                        bool tune) -> std::shared_ptr<ProviderControls> {
                auto controls = std::make_shared<TrayControls>(overlay, status, presets_file, pairing_url,
                                                               [] { ::kill(::getpid(), SIGTERM); });
                if (tune) controls->show_tuning();
                if (!controls->has_tray() && overlay)
                    std::cerr << "umf-provider: no system tray here; --tune opens the tuning window\n";
                return controls;
            };
        return run_serve(args, hooks);
    }
    if (command == "pair")
        return run_pair(parse_command_args(argc, argv, first, {"port", "host", "config-dir"}, {"rotate", "root", "field", "no-qr"}));
    if (command == "trust")
        return run_trust(parse_command_args(argc, argv, first, {"port", "host", "config-dir"}, {"der", "mobileconfig"}, 2));
    if (command == "share")
        return run_share(parse_command_args(argc, argv, first, {"rect", "title", "screen", "port", "remove"}, {"list"}, 1));
    if (command == "puts")
        return run_puts(parse_command_args(argc, argv, first, {"port", "accept", "dismiss"}, {"open", "always", "json"}));
    if (command == "compose") {
        const auto args = parse_command_args(argc, argv, first, umf::provider::compose_options(),
                                             umf::provider::compose_flags());
        const auto config_dir = config_dir_option(args);
        auto compose_args = args;  // compose's own options only
        compose_args.named.erase("config-dir");
        auto app = make_gui_application(argc, argv, true);
        return run_compose(compose_args, config_dir);
    }
    if (command == "browser")
        return run_browser(parse_command_args(argc, argv, first, {"host", "prefix", "port"}, {"system", "json"}, 1));
    if (command == "kde") {
        if (first >= argc || std::strcmp(argv[first], "install") != 0 || first + 1 != argc)
            throw umf::cli::UsageError("kde takes one word: install");
        return run_kde_install(std::cout, std::cerr);
    }
    if (command == "autostart") {
        std::optional<bool> on;
        if (first + 1 == argc && std::strcmp(argv[first], "on") == 0) on = true;
        else if (first + 1 == argc && std::strcmp(argv[first], "off") == 0) on = false;
        else if (first != argc) throw umf::cli::UsageError("autostart takes on, off or nothing");
        return run_autostart(on, std::cout, std::cerr);
    }
    if (command == "gnome") {
        if (first >= argc || std::strcmp(argv[first], "install") != 0 || first + 1 != argc)
            throw umf::cli::UsageError("gnome takes one word: install");
        return run_gnome_install(std::cout, std::cerr);
    }
    throw umf::cli::UsageError("unknown command " + command);
}

}  // namespace umf::provider
