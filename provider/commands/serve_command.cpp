#include "commands/serve_command.hpp"

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
#include <thread>

#include "board/board.hpp"
#include "commands/common_options.hpp"
#include "commands/control_client.hpp"
#include "commands/preset_options.hpp"
#include "commands/serve_parts.hpp"
#include "content/board_resolver.hpp"
#include "content/image_snapshot.hpp"
#include "content/shared_items.hpp"
#include "content/shared_items_file.hpp"
#include "desktop/open_desktop.hpp"
#include "desktop/session.hpp"
#include "field_overlay/overlay_activity.hpp"
#include "put/put_deciders.hpp"
#include "put/put_prompt_window.hpp"
#include "server/console_activity.hpp"
#include "field_overlay/overlay_manager.hpp"
#include "overlay/preset.hpp"
#include "screen/desktop_layout.hpp"
#include "screen/board_window.hpp"
#include "screen/screen_field.hpp"
#include "screen/screen_image.hpp"
#include "server/config_dir.hpp"
#include "browser/browser_link.hpp"
#include "browser/browser_resolver.hpp"
#include "server/control_socket.hpp"
#include "server/pairing.hpp"
#include "server/pairing_qr.hpp"
#include "server/server.hpp"
#include "server/service.hpp"
#include "server/static_site.hpp"
#include "server/tls_identity.hpp"

namespace umf::provider {

const char* const kServeOptions[] = {"port",         "bind",        "host",   "config-dir", "board",
                                     "preset",       "screen",      "web",    "opacity-min", "opacity-max",
                                     "period",       "waveform",    "module-px", "blur",     "region",
                                     "focus-radius", "activation",  "fade",   "palette",     "puts",
                                     "put-dir",      "put-max-mb",  "desktop",     nullptr};
const char* const kServeFlags[] = {"headless", "public", "no-qr", "no-overlay", "tune", nullptr};

namespace {

using cli::get;
using cli::has_flag;
using cli::UsageError;

// PREFIX/share/umf/web for an installed provider (found from the program's
// own place, so any prefix works), else the build tree's web/site.
std::optional<std::filesystem::path> default_web_dir() {
    std::error_code ec;
    const auto self = std::filesystem::read_symlink("/proc/self/exe", ec);
    if (!ec) {
        const auto installed = self.parent_path().parent_path() / "share" / "umf" / "web";
        if (std::filesystem::is_regular_file(installed / "index.html", ec)) return installed;
    }
#ifdef UMF_WEB_SITE_DIR
    if (std::filesystem::is_directory(UMF_WEB_SITE_DIR, ec)) return std::filesystem::path(UMF_WEB_SITE_DIR);
#endif
    return std::nullopt;
}

bool have_display() {
    const char* x = std::getenv("DISPLAY");
    const char* w = std::getenv("WAYLAND_DISPLAY");
    return (x && *x) || (w && *w);
}

overlay::Preset preset_option(const cli::Args& a, const std::filesystem::path& config_dir, bool board) {
    std::vector<overlay::Preset> presets = overlay::built_in_presets();
    const auto user_file = config_dir / "presets.json";
    std::error_code ec;
    if (std::filesystem::exists(user_file, ec))
        for (auto& p : overlay::load_presets(user_file.string())) presets.push_back(std::move(p));
    // Boards and kiosks are there to be pointed at: their field is always up.
    const std::string name = get(a, "preset").value_or(board ? "kiosk" : "balanced");
    // User presets come last and win over a built-in of the same name.
    for (auto it = presets.rbegin(); it != presets.rend(); ++it)
        if (it->name == name) return *it;
    std::string names;
    for (const auto& p : presets) names += (names.empty() ? "" : ", ") + p.name;
    throw UsageError("no preset called \"" + name + "\"; there are " + names);
}

// What was shared before this provider was started again by its keeper
// comes back, and every change is written down for the next one.
void keep_shared_items(SharedItems& items, const std::filesystem::path& file) {
    try {
        const int restored = items.restore(load_shared_items(file));
        if (restored > 0) std::cout << "shared: " << restored << " item(s) shared before are served again\n";
    } catch (const std::exception& e) {
        std::cerr << "umf-provider: " << e.what() << "; the items shared before are gone\n";
    }
    items.on_change([file](const std::vector<SharedItem>& now) {
        try {
            save_shared_items(file, now);
        } catch (const std::exception& e) {
            std::cerr << "umf-provider: " << e.what() << "; shared items will not survive a restart\n";
        }
    });
}

}  // namespace

int run_serve(const cli::Args& a, const ServeHooks& hooks) {
    const unsigned short port = port_option(a);
    const std::string bind = get(a, "bind").value_or("127.0.0.1");
    const std::string host = url_host(a, bind);
    const auto dir = config_dir_option(a);
    DesktopChoice desktop_choice;
    try {
        desktop_choice = choose_desktop(session_from_environment(), get(a, "desktop"));
    } catch (const std::invalid_argument& e) {
        throw UsageError(e.what());
    }
    const bool headless = has_flag(a, "headless") || !have_display() || desktop_choice.kind == DesktopKind::headless;
    const bool public_mode = has_flag(a, "public");
    const PutChoice puts = put_choice(a, dir, public_mode);
    const std::string& puts_mode = puts.mode;
    const PutSettings& put_settings = puts.settings;
    if (puts_mode != "never") {
        std::error_code ec;
        std::filesystem::create_directories(put_settings.folder, ec);
        if (!std::filesystem::is_directory(put_settings.folder, ec)) {
            std::cerr << "umf-provider: the put folder " << put_settings.folder.string() << " cannot be made\n";
            return kConfigError;
        }
    }

    TlsIdentity identity;
    std::string token;
    try {
        identity = load_or_create_tls_identity(dir);
        token = load_or_create_token(dir);
    } catch (const std::exception& e) {
        std::cerr << "umf-provider: " << e.what() << "\n";
        return kConfigError;
    }

    // The screen: virtual when headless, the primary one otherwise (more
    // screens come with the overlay).
    std::pair<int, int> size{1920, 1080};
    if (!headless) {
        if (QScreen* s = QGuiApplication::primaryScreen()) {
            const QSize px = s->size() * s->devicePixelRatio();
            size = {px.width(), px.height()};
        }
    }
    size = screen_size_option(a, "screen", size);
    const auto [width, height] = size;

    std::optional<Board> board;
    std::filesystem::path board_source;
    try {
        if (auto file = get(a, "board")) {
            board = load_board(*file);
            board_source = *file;
        } else if (headless) {
            board_source = dir / "demo-board";
            board = write_demo_board(board_source);
        }
    } catch (const std::exception& e) {
        std::cerr << "umf-provider: " << e.what() << "\n";
        return kConfigError;
    }
    if (public_mode && !board) throw UsageError("--public needs a board: it serves board items and nothing else");
    const overlay::Preset preset = apply_preset_options(preset_option(a, dir, board.has_value()), a);
    // The board's field: the preset's module size, on a real screen scaled by
    // its density; a virtual screen counts as 96 dpi, as compose does.
    double board_module_px = preset.module_px;
    if (!headless)
        if (QScreen* s = QGuiApplication::primaryScreen())
            board_module_px = module_px_for_density(preset.module_px, s->physicalDotsPerInch() * s->devicePixelRatio());

    // The desktop (desktop/desktop.hpp): its field, its windows, its pixels.
    // A Wayland session without a backend gets none, and no overlay at all.
    OpenedDesktop desktop;
    if (!headless) desktop = open_desktop(desktop_choice);
    // On a desktop without a board: the overlay over every screen, when the
    // desktop can show it (on X11: a compositor mixes it in).
    std::unique_ptr<OverlayManager> overlay_manager;
    std::shared_ptr<OverlayActivity> activity;
    std::optional<DesktopLayout> layout;
    if (!headless && !board && !has_flag(a, "no-overlay")) {
        if (!desktop.desktop || !desktop.abilities.field) {
            std::cerr << "umf-provider: the field cannot be shown on this desktop; the desktop lines on the console say why\n";
        } else {
            overlay_manager = std::make_unique<OverlayManager>(preset, desktop.desktop);
            layout = overlay_manager->layout();
            activity = std::make_shared<OverlayActivity>(overlay_manager.get(), overlay_manager->layout_indices());
        }
    }

    const PutAnswerers answerers = put_answerers(puts, headless, overlay_manager.get());
    const std::shared_ptr<ControlPutDecider>& put_answers = answerers.control;
    const std::shared_ptr<PutPromptDecider>& put_prompt = answerers.prompt;
    const std::shared_ptr<PutDecider>& put_decider = answerers.decider;

    std::vector<std::shared_ptr<const Resolver>> resolvers;
    // Browsers tell what their windows show once the server knows its port;
    // only a desktop's windows are looked into.
    std::shared_ptr<BrowserLink> browser_link;
    std::shared_ptr<BrowserResolver> browsers;
    auto shared_items = std::make_shared<SharedItems>();
    if (hooks.keeper) keep_shared_items(*shared_items, hooks.keeper->shares_file);
    QImage screen_image(width, height, QImage::Format_RGB32);
    screen_image.fill(Qt::black);
    if (board) {
        auto tiles = layout_board(*board, width, height);
        screen_image = paint_board(*board, tiles, QSize(width, height));
        resolvers.push_back(std::make_shared<BoardResolver>(*board, std::move(tiles)));
    }
    if (!public_mode) {
        resolvers.push_back(shared_items);
        if (headless) {
            resolvers.push_back(std::make_shared<ImageSnapshotResolver>(screen_image));
        } else if (desktop.desktop && desktop.abilities.windows) {
            // The windows under the point, never the provider's own.
            try {
                add_window_resolvers(desktop, overlay_manager.get(), put_prompt.get(), resolvers, browser_link,
                                     browsers);
            } catch (const std::exception& e) {
                std::cerr << "umf-provider: windows cannot be looked up (" << e.what()
                          << "); serving board and shared items only\n";
            }
        }
    }

    // The web client: --web DIR, else the installed one beside this program,
    // else the one this build made, else the built-in page (std::nullopt).
    std::optional<std::filesystem::path> web_dir;
    if (auto web = get(a, "web")) {
        web_dir = *web;
    } else {
        web_dir = default_web_dir();
    }
    std::shared_ptr<const StaticSite> site;
    try {
        if (web_dir) site = std::make_shared<const StaticSite>(StaticSite::from_folder(*web_dir));
    } catch (const std::exception& e) {
        std::cerr << "umf-provider: " << e.what() << "\n";
        return kConfigError;
    }

    // SIGINT and SIGTERM are taken with sigwait below; blocked before any
    // thread starts, so none of the server's threads receives them.
    sigset_t signals;
    sigemptyset(&signals);
    sigaddset(&signals, SIGINT);
    sigaddset(&signals, SIGTERM);
    pthread_sigmask(SIG_BLOCK, &signals, nullptr);

    std::unique_ptr<Server> server;
    std::unique_ptr<ControlSocket> control;
    try {
        ServiceConfig config = layout ? service_config_for(*layout)
                                      : default_service_config(width, height, headless ? "headless" : "screen",
                                                               board_module_px);
        config.overlay = overlay_info(preset);
        config.public_mode = public_mode;
        config.put_decider = put_decider;
        config.puts = put_settings;
        if (browsers)
            config.puts.open_url_at = [browsers](const ScreenPoint& at, const std::string& url) {
                return browsers->open_tab_at(at, url);
            };
        if (desktop.desktop && desktop.abilities.placement)
            config.puts.watch_new_window = [d = desktop.desktop](const WindowPlacement& where) {
                return d->watch_new_window(where);
            };
        // Who connects and what they take, on the console; the overlay hears it all.
        auto console = std::make_shared<ConsoleActivity>(std::cout, activity);
        auto service = std::make_shared<Service>(std::move(config), token, resolvers, site, console);
        if (overlay_manager) {
            // Screens that come, go or change move the field: new sessions
            // get the new one, older ones are told to connect again.
            OverlayManager* m = overlay_manager.get();
            overlay_manager->on_screens_changed([m, activity, weak = std::weak_ptr<Service>(service)] {
                const auto service = weak.lock();
                if (!service || !m->layout()) return;
                activity->set_screen_indices(m->layout_indices());
                service->set_screens(*m->layout());
                std::cout << "overlay: screens changed: " << m->layout()->screens.size() << " screen(s), field "
                          << m->layout()->field.id << "\n" << std::flush;
            });
        }
        if (board) {
            std::vector<std::filesystem::path> files;
            for (const auto& item : board->items)
                if (item.file) files.push_back(*item.file);
            service->prepare_files(files);
        }
        ServerOptions options;
        options.bind_address = bind;
        options.port = port;
        options.threads = 2;
        server = std::make_unique<Server>(service, identity, options);
        server->start();
        if (hooks.keeper) tell_keeper_port(*hooks.keeper, server->port());
        if (browser_link) {
            try {
                browser_link->listen(browser_socket_path(server->port()));
            } catch (const std::exception& e) {
                std::cerr << "umf-provider: no browser companion this time: " << e.what() << "\n";
                browser_link.reset();
            }
        }
        if (!public_mode || put_answers)
            control = std::make_unique<ControlSocket>(control_socket_path(server->port()),
                                                      public_mode ? nullptr : shared_items, put_answers, browser_link);
    } catch (const std::exception& e) {
        std::cerr << "umf-provider: " << e.what() << "\n";
        return kServeError;
    }

    const std::string url = pairing_url(host, server->port(), token, identity.fingerprint);
    std::cout << "umf-provider: listening on https://" << (bind.find(':') != std::string::npos ? "[" + bind + "]" : bind)
              << ":" << server->port() << " (WebSocket at /ws, HTTPS transport under /api/)\n";
    std::cout << "web client: " << (web_dir ? web_dir->string() + " (" + std::to_string(site->size()) + " files)"
                                            : std::string("the built-in page"))
              << "\n";
    if (board)
        std::cout << "board: " << board->items.size() << " items" << (board->title.empty() ? "" : " (" + board->title + ")")
                  << " from " << board_source.string() << "\n";
    std::cout << (headless ? "headless: a virtual " : "screen: ") << width << "x" << height << ", preset "
              << preset.name << (public_mode ? ", public mode (board items only, no pairing needed)" : "") << "\n";
    // The hints name this provider's port when it is not the default one.
    const unsigned short listening = server->port();
    if (control && !public_mode)
        std::cout << "share with: " << with_port("umf-provider share FILE|URL --rect x,y,w,h", listening) << "\n";
    if (browser_link)
        std::cout << "browsers: pointing at a browser window takes its page once the companion is set up "
                     "(umf-provider browser install; "
                  << with_port("umf-provider browser status", listening) << " lists them)\n";
    std::cout << "puts: "
              << (put_decider ? puts_mode + ", files to " + put_settings.folder.string() +
                                    (put_answers ? " (answer with: " + with_port("umf-provider puts", listening) + ")" : "")
                              : std::string("off"))
              << "\n";
    std::cout << "certificate fingerprint (SHA-256): " << identity.fingerprint << "\n";
    if (!has_flag(a, "no-qr")) std::cout << qr_text(url);
    std::cout << "pairing URL: " << url << "\n" << std::flush;

    for (const auto& line : describe_desktop(desktop)) std::cout << line << "\n";
    std::cout << std::flush;
    if (layout) {
        std::cout << "overlay: " << layout->screens.size() << " screen(s), field " << layout->field.id << ", preset "
                  << preset.name << " (" << overlay::to_string(preset.activation) << ")\n" << std::flush;
    }
    int received = 0;
    std::unique_ptr<BoardWindow> board_window;
    if (!headless && board) {
        board_window = std::make_unique<BoardWindow>(screen_image, screen_field_for(width, height, board_module_px),
                                                     preset, QGuiApplication::primaryScreen());
        board_window->showFullScreen();
    }
    std::shared_ptr<ProviderControls> controls;
    if (!headless && !board && hooks.desktop_controls) {
        try {
            controls = hooks.desktop_controls(overlay_manager.get(), desktop_summary(desktop),
                                              (dir / "presets.json").string(), url, has_flag(a, "tune"));
        } catch (const std::exception& e) {
            std::cerr << "umf-provider: no tray or tuning window: " << e.what() << "\n";
        }
    }
    if (controls && desktop.desktop)
        desktop.desktop->on_abilities_changed([&desktop, weak = std::weak_ptr<ProviderControls>(controls)] {
            desktop.abilities = desktop.desktop->abilities();
            if (const auto c = weak.lock()) c->set_status(desktop_summary(desktop));
        });
    if (board_window || overlay_manager || put_prompt || controls) {
        // Windows are up: the Qt event loop runs here, and a thread waits for
        // the signals, stops the server (whose snapshots may wait on this
        // loop) and then ends the loop.
        std::atomic<int> got{0};
        std::thread waiter([&] {
            int signal = 0;
            sigwait(&signals, &signal);
            got = signal;
            std::cerr << "umf-provider: " << (signal == SIGINT ? "SIGINT" : "SIGTERM") << ", closing sessions\n";
            control.reset();
            server->stop();
            QMetaObject::invokeMethod(qApp, [] { QCoreApplication::quit(); }, Qt::QueuedConnection);
        });
        QGuiApplication::exec();
        if (desktop.desktop) desktop.desktop->on_abilities_changed({});
        if (got == 0) ::kill(::getpid(), SIGTERM);  // the loop ended otherwise: release the waiter
        waiter.join();
        std::cerr << "umf-provider: stopped\n";
        return kOk;
    }
    sigwait(&signals, &received);
    std::cerr << "umf-provider: " << (received == SIGINT ? "SIGINT" : "SIGTERM") << ", closing sessions\n";
    control.reset();
    server->stop();
    std::cerr << "umf-provider: stopped\n";
    return kOk;
}

}  // namespace umf::provider
