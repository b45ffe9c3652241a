#include "provider/commands/serve_command.hpp"

#include <pthread.h>
#include <unistd.h>
#include <signal.h>

#include <QGuiApplication>
#include <QScreen>
#include <cstdlib>
#include <iostream>
#include <chrono>
#include <memory>
#include <atomic>
#include <stdexcept>
#include <thread>
#include <tuple>

#include "provider/board/board.hpp"
#include "provider/browser/browser_link.hpp"
#include "provider/browser/browser_resolver.hpp"
#include "provider/commands/common_options.hpp"
#include "provider/commands/control_client.hpp"
#include "provider/commands/preset_options.hpp"
#include "provider/commands/serve_field.hpp"
#include "provider/commands/serve_parts.hpp"
#include "provider/commands/serve_reach.hpp"
#include "provider/common/config_dir.hpp"
#include "provider/common/install_paths.hpp"
#include "provider/content/board_resolver.hpp"
#include "provider/content/image_snapshot.hpp"
#include "provider/content/shared_items.hpp"
#include "provider/desktop/desktop_choice.hpp"
#include "provider/desktop/open_desktop.hpp"
#include "provider/field_overlay/overlay_activity.hpp"
#include "provider/field_overlay/overlay_manager.hpp"
#include "provider/put/put_deciders.hpp"
#include "provider/put/put_prompt_window.hpp"
#include "provider/screen/board_window.hpp"
#include "provider/screen/desktop_layout.hpp"
#include "provider/screen/screen_field.hpp"
#include "provider/screen/screen_image.hpp"
#include "provider/service/console_activity.hpp"
#include "provider/service/control_socket.hpp"
#include "provider/service/pairing.hpp"
#include "provider/service/pairing_qr.hpp"
#include "provider/service/service.hpp"
#include "provider/service/service_server.hpp"
#include "provider/service/static_site.hpp"
#include "provider/trust/tls_identity_store.hpp"
#include "shared/overlay/preset.hpp"

namespace umf::provider {

const char* const kServeOptions[] = {"port",         "bind",        "host",   "config-dir", "board",
                                     "preset",       "screen",      "web",    "opacity-min", "opacity-max",
                                     "period",       "waveform",    "module-px", "blur",     "region",
                                     "focus-radius", "activation",  "fade",   "palette",     "puts",
                                     "put-dir",      "put-max-mb",  "desktop",     nullptr};
const char* const kServeFlags[] = {"headless", "public",        "no-qr",     "no-overlay", "tune",
                                   "no-announce", "shipped-field", "own-field", nullptr};

namespace {

using cli::get;
using cli::has_flag;
using cli::UsageError;

bool have_display() {
    const char* x = std::getenv("DISPLAY");
    const char* w = std::getenv("WAYLAND_DISPLAY");
    return (x && *x) || (w && *w);
}

// A step that cannot go on: the message for the console and the exit code.
struct ServeFailure : std::runtime_error {
    ServeFailure(int code_, const std::string& message) : std::runtime_error(message), code(code_) {}
    int code;
};

// Everything a running provider holds, filled in step by step by run_serve.
struct Serving {
    // The command line.
    unsigned short port = 0;
    std::string bind, host;
    std::filesystem::path dir;
    DesktopChoice desktop_choice;
    bool headless = false;
    bool public_mode = false;
    PutChoice puts;
    // Identity, screen, board and preset.
    TlsIdentity identity;
    RootAuthority root;  // the identity's root, offered to the phone page
    ServingNames names;  // what the serving certificate names
    std::string token;
    int width = 1920, height = 1080;
    std::optional<Board> board;
    std::filesystem::path board_source;
    overlay::Preset preset;
    double board_module_px = 0;
    FieldSource fields;  // the screen's own, or with --shipped-field the shipped fields
    // The desktop and the overlay over it.
    OpenedDesktop desktop;
    std::unique_ptr<OverlayManager> overlay_manager;
    std::shared_ptr<OverlayActivity> activity;
    std::optional<DesktopLayout> layout;
    // What lies under a point and who answers puts.
    PutAnswerers answerers;
    std::vector<std::shared_ptr<const Resolver>> resolvers;
    std::shared_ptr<BrowserLink> browser_link;
    std::shared_ptr<BrowserResolver> browsers;
    std::shared_ptr<SharedItems> shared_items = std::make_shared<SharedItems>();
    QImage screen_image;
    std::optional<std::filesystem::path> web_dir;
    std::shared_ptr<const StaticSite> site;
    // Running.
    sigset_t signals{};
    std::unique_ptr<Server> server;
    std::unique_ptr<CertificateKeeper> certificate_keeper;  // after server: calls into it, so ends first
    // The .local name Avahi announced this host by, when it differs from the
    // host name's: the serving certificate names it too.
    std::shared_ptr<LocalName> local_name = std::make_shared<LocalName>();
    std::unique_ptr<AvahiAnnouncement> announcement;
    std::shared_ptr<NearbyScreens> nearby = std::make_shared<NearbyScreens>();  // for /nearby.json
    std::unique_ptr<NearbyBrowse> nearby_browse;
    std::unique_ptr<ControlSocket> control;
    std::string url;
    std::shared_ptr<Service> service;
    std::unique_ptr<BoardWindow> board_window;  // a board on a screen
};

void read_command_line(const cli::Args& a, Serving& s) {
    s.port = port_option(a);
    // Phones must reach it: every address unless told otherwise.
    s.bind = get(a, "bind").value_or("0.0.0.0");
    s.host = url_host(a, s.bind);
    s.dir = config_dir_option(a);
    // --own-field, the default, is still taken from the command lines of
    // before it was.
    if (!has_flag(a, "shipped-field")) {
        try {
            s.fields = own_field_source(s.dir);
        } catch (const std::runtime_error& e) {
            throw ServeFailure(kConfigError, e.what());
        }
    }
    try {
        s.desktop_choice = choose_desktop(desktop_facts_from_environment(), get(a, "desktop"));
    } catch (const std::invalid_argument& e) {
        throw UsageError(e.what());
    }
    s.headless = has_flag(a, "headless") || !have_display() || s.desktop_choice.kind == DesktopKind::headless;
    s.public_mode = has_flag(a, "public");
    s.puts = put_choice(a, s.dir, s.public_mode);
    if (s.puts.mode != "never") {
        std::error_code ec;
        std::filesystem::create_directories(s.puts.settings.folder, ec);
        if (!std::filesystem::is_directory(s.puts.settings.folder, ec))
            throw ServeFailure(kConfigError, "the put folder " + s.puts.settings.folder.string() + " cannot be made");
    }
}

void load_identity(Serving& s) {
    try {
        s.names = current_serving_names();
        const LoadedIdentity loaded = load_or_issue_tls_identity(s.dir, s.names, std::chrono::system_clock::now());
        s.identity = loaded.identity;
        s.root = loaded.root;
        if (!loaded.issued_because.empty())
            std::cout << "certificate: issued by the screen's root (" << loaded.issued_because << ")\n";
        s.token = load_or_create_token(s.dir);
    } catch (const std::exception& e) {
        throw ServeFailure(kConfigError, e.what());
    }
}

// The screen (virtual when headless, the primary one otherwise: more screens
// come with the overlay), the board, the preset and the board's module size.
void choose_screen_board_and_preset(const cli::Args& a, Serving& s) {
    std::pair<int, int> size{1920, 1080};
    if (!s.headless) {
        if (QScreen* screen = QGuiApplication::primaryScreen()) {
            const QSize px = screen->size() * screen->devicePixelRatio();
            size = {px.width(), px.height()};
        }
    }
    std::tie(s.width, s.height) = screen_size_option(a, "screen", size);
    try {
        if (auto file = get(a, "board")) {
            s.board = load_board(*file);
            s.board_source = *file;
        } else if (s.headless) {
            s.board_source = s.dir / "demo-board";
            s.board = write_demo_board(s.board_source);
        }
    } catch (const std::exception& e) {
        throw ServeFailure(kConfigError, e.what());
    }
    if (s.public_mode && !s.board) throw UsageError("--public needs a board: it serves board items and nothing else");
    s.preset = apply_preset_options(preset_option(a, s.dir, s.board.has_value()), a);
    // The preset's module size, on a real screen scaled by its density; a
    // virtual screen counts as 96 dpi, as compose does.
    s.board_module_px = s.preset.module_px;
    if (!s.headless)
        if (QScreen* screen = QGuiApplication::primaryScreen())
            s.board_module_px =
                module_px_for_density(s.preset.module_px, screen->physicalDotsPerInch() * screen->devicePixelRatio());
}

// The desktop (desktop/desktop.hpp: its field, windows, pixels); a Wayland
// session without a backend gets none, and no overlay at all. On a desktop
// without a board: the overlay over every screen, when the desktop can show
// it (on X11: a compositor mixes it in).
void open_desktop_and_overlay(const cli::Args& a, Serving& s) {
    if (!s.headless) s.desktop = open_desktop(s.desktop_choice);
    if (s.headless || s.board || has_flag(a, "no-overlay")) return;
    if (!s.desktop.desktop || !s.desktop.abilities.field) {
        std::cerr << "umf-provider: the field cannot be shown on this desktop; the desktop lines on the console say why\n";
        return;
    }
    s.overlay_manager = std::make_unique<OverlayManager>(s.preset, s.desktop.desktop, s.fields);
    s.layout = s.overlay_manager->layout();
    s.activity = std::make_shared<OverlayActivity>(s.overlay_manager.get(), s.overlay_manager->layout_indices());
}

// Resolvers in order: the board, shared items, then a headless screen's
// snapshot or a desktop's windows (never the provider's own); browsers tell
// what their windows show once the server knows its port.
void gather_resolvers(const ServeHooks& hooks, Serving& s) {
    s.answerers = put_answerers(s.puts, s.headless, s.overlay_manager.get());
    if (hooks.keeper) keep_shared_items(*s.shared_items, hooks.keeper->shares_file);
    s.screen_image = QImage(s.width, s.height, QImage::Format_RGB32);
    s.screen_image.fill(Qt::black);
    if (s.board) {
        auto tiles = layout_board(*s.board, s.width, s.height);
        s.screen_image = paint_board(*s.board, tiles, QSize(s.width, s.height));
        s.resolvers.push_back(std::make_shared<BoardResolver>(*s.board, std::move(tiles)));
    }
    if (s.public_mode) return;
    s.resolvers.push_back(s.shared_items);
    if (s.headless) {
        s.resolvers.push_back(std::make_shared<ImageSnapshotResolver>(s.screen_image));
    } else if (s.desktop.desktop && s.desktop.abilities.windows) {
        try {
            add_window_resolvers(s.desktop, s.overlay_manager.get(), s.answerers.prompt.get(), s.resolvers,
                                 s.browser_link, s.browsers);
        } catch (const std::exception& e) {
            std::cerr << "umf-provider: windows cannot be looked up (" << e.what()
                      << "); serving board and shared items only\n";
        }
    }
}

// The web client: --web DIR, else the installed one beside this program,
// else the one this build made, else the built-in page (no site).
void load_web_client(const cli::Args& a, Serving& s) {
    if (auto web = get(a, "web"))
        s.web_dir = *web;
    else
        s.web_dir = web_site_dir();
    try {
        auto site = std::make_shared<StaticSite>(s.web_dir ? StaticSite::from_folder(*s.web_dir) : StaticSite());
        offer_root(*site, s.root);
        s.site = std::move(site);
    } catch (const std::exception& e) {
        throw ServeFailure(kConfigError, e.what());
    }
}

// SIGINT and SIGTERM are taken with sigwait; blocked before any thread
// starts, so none of the server's threads receives them.
void block_stop_signals(Serving& s) {
    sigemptyset(&s.signals);
    sigaddset(&s.signals, SIGINT);
    sigaddset(&s.signals, SIGTERM);
    pthread_sigmask(SIG_BLOCK, &s.signals, nullptr);
}

std::shared_ptr<Service> make_service(Serving& s) {
    ServiceConfig config = s.layout ? service_config_for(*s.layout)
                                    : default_service_config(s.width, s.height, s.headless ? "headless" : "screen",
                                                             s.board_module_px, s.fields);
    config.overlay = overlay_info(s.preset);
    config.public_mode = s.public_mode;
    config.put_decider = s.answerers.decider;
    config.puts = s.puts.settings;
    config.nearby = s.nearby;
    if (s.browsers)
        config.puts.open_url_at = [browsers = s.browsers](const ScreenPoint& at, const std::string& url) {
            return browsers->open_tab_at(at, url);
        };
    if (s.desktop.desktop && s.desktop.abilities.placement)
        config.puts.watch_new_window = [d = s.desktop.desktop](const WindowPlacement& where) {
            return d->watch_new_window(where);
        };
    // Who connects and what they take, on the console; the overlay hears it all.
    auto console = std::make_shared<ConsoleActivity>(std::cout, s.activity);
    auto service = std::make_shared<Service>(std::move(config), s.token, s.resolvers, s.site, console);
    if (s.overlay_manager) {
        // Screens that come, go or change move the field: new sessions get
        // the new one, older ones are told to connect again.
        OverlayManager* m = s.overlay_manager.get();
        s.overlay_manager->on_screens_changed([m, activity = s.activity, weak = std::weak_ptr<Service>(service)] {
            const auto service = weak.lock();
            if (!service || !m->layout()) return;
            activity->set_screen_indices(m->layout_indices());
            service->set_screens(*m->layout());
            std::cout << "overlay: screens changed: " << m->layout()->screens.size() << " screen(s), field "
                      << m->layout()->field.id << "\n" << std::flush;
        });
    }
    if (s.board) {
        std::vector<std::filesystem::path> files;
        for (const auto& item : s.board->items)
            if (item.file) files.push_back(*item.file);
        service->prepare_files(files);
    }
    return service;
}

// The service, the server on its port, the browser link and the control socket.
void start_server(const ServeHooks& hooks, Serving& s) {
    try {
        s.service = make_service(s);
        ServerOptions options;
        options.bind_address = s.bind;
        options.port = s.port;
        options.threads = 2;
        s.server = make_server(s.service, s.identity, options);
        s.server->start();
        s.certificate_keeper = keep_certificate(s.dir, *s.server, s.local_name, s.names);
        if (hooks.keeper) tell_keeper_port(*hooks.keeper, s.server->port());
        if (s.browser_link) {
            try {
                s.browser_link->listen(browser_socket_path(s.server->port()));
            } catch (const std::exception& e) {
                std::cerr << "umf-provider: no browser companion this time: " << e.what() << "\n";
                s.browser_link.reset();
            }
        }
        s.control = std::make_unique<ControlSocket>(control_socket_path(s.server->port()),
                                                    s.public_mode ? nullptr : s.shared_items, s.answerers.control,
                                                    s.browser_link, [&s] {
                                                        s.service->set_token(load_or_create_token(s.dir));
                                                        return RotatedRead{s.dir, show_own_field_from_any_thread(
                                                            {s.dir, s.fields, *s.service, s.overlay_manager.get(),
                                                             s.board_window.get(), s.screen_image, s.width, s.height,
                                                             s.board_module_px, s.headless ? "headless" : "screen"})};
                                                    });
    } catch (const std::exception& e) {
        throw ServeFailure(kServeError, e.what());
    }
    // The .local name goes along (requesters try it when the address fails)
    // unless this provider serves its own machine only.
    const std::string name = s.local_name->get();
    s.url = pairing_url(s.host, s.server->port(), s.token, s.identity.fingerprint,
                        is_loopback(s.bind) || s.host == name ? std::string() : name);
}

// A provider that serves this machine only announces nothing.
void announce(const cli::Args& a, Serving& s) {
    if (is_loopback(s.bind) || has_flag(a, "no-announce")) return;
    s.announcement = announce_on_network(s.server->port(), s.identity.fingerprint, s.local_name);
    s.nearby_browse = browse_nearby(s.identity.fingerprint, s.nearby);
}

void print_banner(const cli::Args& a, const Serving& s) {
    const unsigned short listening = s.server->port();
    std::cout << "umf-provider: listening on https://"
              << (s.bind.find(':') != std::string::npos ? "[" + s.bind + "]" : s.bind) << ":" << listening
              << " (WebSocket at /ws, HTTPS transport under /api/)\n";
    std::cout << "web client: "
              << (s.web_dir ? s.web_dir->string() + " (" + std::to_string(s.site->size()) + " files)"
                            : std::string("the built-in page"))
              << "\n";
    if (s.board)
        std::cout << "board: " << s.board->items.size() << " items"
                  << (s.board->title.empty() ? "" : " (" + s.board->title + ")") << " from " << s.board_source.string()
                  << "\n";
    std::cout << (s.headless ? "headless: a virtual " : "screen: ") << s.width << "x" << s.height << ", preset "
              << s.preset.name << (s.public_mode ? ", public mode (board items only, no pairing needed)" : "");
    if (!s.layout)
        std::cout << ", field " << screen_field_for(s.width, s.height, s.board_module_px, s.fields).field.id
                  << (s.fields.own() ? " (this screen's own)" : " (shipped)");
    std::cout << "\n";
    // The hints name this provider's port when it is not the default one.
    if (s.control && !s.public_mode)
        std::cout << "share with: " << with_port("umf-provider share FILE|URL --rect x,y,w,h", listening) << "\n";
    if (s.browser_link)
        std::cout << "browsers: pointing at a browser window takes its page once the companion is set up "
                     "(umf-provider browser install; "
                  << with_port("umf-provider browser status", listening) << " lists them)\n";
    const PutSettings& settings = s.puts.settings;
    std::cout << "puts: "
              << (s.answerers.decider
                      ? s.puts.mode + ", files to " + settings.folder.string() +
                            (s.answerers.control ? " (answer with: " + with_port("umf-provider puts", listening) + ")"
                                                 : "")
                      : std::string("off"))
              << "\n";
    print_where_served(s.bind, s.server->port(), s.names, s.identity.fingerprint, std::cout);
    if (!has_flag(a, "no-qr")) std::cout << qr_text(s.url);
    std::cout << "pairing URL: " << s.url << "\n" << std::flush;
    for (const auto& line : describe_desktop(s.desktop)) std::cout << line << "\n";
    std::cout << std::flush;
    if (s.layout)
        std::cout << "overlay: " << s.layout->screens.size() << " screen(s), field " << s.layout->field.id
                  << ", preset " << s.preset.name << " (" << overlay::to_string(s.preset.activation) << ")\n"
                  << std::flush;
}

// Until SIGINT or SIGTERM. With windows up, the Qt event loop runs here and
// a thread waits for the signals, stops the server (whose snapshots may wait
// on this loop) and then ends the loop.
int run_until_stopped(const cli::Args& a, const ServeHooks& hooks, Serving& s) {
    auto& board_window = s.board_window;
    if (!s.headless && s.board) {
        board_window = std::make_unique<BoardWindow>(
            s.screen_image, screen_field_for(s.width, s.height, s.board_module_px, s.fields), s.preset,
            QGuiApplication::primaryScreen());
        board_window->showFullScreen();
    }
    std::shared_ptr<ProviderControls> controls;
    if (!s.headless && !s.board && hooks.desktop_controls) {
        try {
            controls = hooks.desktop_controls(s.overlay_manager.get(), desktop_summary(s.desktop),
                                              (s.dir / "presets.json").string(), s.url, has_flag(a, "tune"));
        } catch (const std::exception& e) {
            std::cerr << "umf-provider: no tray or tuning window: " << e.what() << "\n";
        }
    }
    if (controls && s.desktop.desktop)
        s.desktop.desktop->on_abilities_changed([&desktop = s.desktop, weak = std::weak_ptr<ProviderControls>(controls)] {
            desktop.abilities = desktop.desktop->abilities();
            if (const auto c = weak.lock()) c->set_status(desktop_summary(desktop));
        });
    if (board_window || s.overlay_manager || s.answerers.prompt || controls) {
        std::atomic<int> got{0};
        std::thread waiter([&] {
            int signal = 0;
            sigwait(&s.signals, &signal);
            got = signal;
            std::cerr << "umf-provider: " << (signal == SIGINT ? "SIGINT" : "SIGTERM") << ", closing sessions\n";
            s.control.reset();
            s.server->stop();
            QMetaObject::invokeMethod(qApp, [] { QCoreApplication::quit(); }, Qt::QueuedConnection);
        });
        QGuiApplication::exec();
        if (s.desktop.desktop) s.desktop.desktop->on_abilities_changed({});
        if (got == 0) ::kill(::getpid(), SIGTERM);  // the loop ended otherwise: release the waiter
        waiter.join();
        std::cerr << "umf-provider: stopped\n";
        return kOk;
    }
    int received = 0;
    sigwait(&s.signals, &received);
    std::cerr << "umf-provider: " << (received == SIGINT ? "SIGINT" : "SIGTERM") << ", closing sessions\n";
    s.control.reset();
    s.server->stop();
    std::cerr << "umf-provider: stopped\n";
    return kOk;
}

}  // namespace

int run_serve(const cli::Args& a, const ServeHooks& hooks) {
    Serving s;
    try {
        read_command_line(a, s);
        load_identity(s);
        choose_screen_board_and_preset(a, s);
        open_desktop_and_overlay(a, s);
        gather_resolvers(hooks, s);
        load_web_client(a, s);
        block_stop_signals(s);
        start_server(hooks, s);
    } catch (const ServeFailure& e) {
        std::cerr << "umf-provider: " << e.what() << "\n";
        return e.code;
    }
    print_banner(a, s);
    announce(a, s);
    return run_until_stopped(a, hooks, s);
}

}  // namespace umf::provider
