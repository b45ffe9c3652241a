// The X11 window and snapshot resolvers against a real X server: Xvfb with
// openbox as window manager, mupdf showing a PDF and an xterm, placed with
// xdotool. Skipped when those programs are missing (Debian: xvfb openbox
// mupdf xterm xdotool). Also the parts that need no X server: snapshot
// names and rectangles, PNG encoding, mime types.
#ifdef UMF_PROVIDER_TESTS

#include <fcntl.h>
#include <gtest/gtest.h>
#include <poll.h>
#include <signal.h>
#include <stdlib.h>
#include <sys/prctl.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include <QByteArray>
#include <QImage>
#include <atomic>
#include <chrono>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <map>
#include <memory>
#include <optional>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

#include "provider/content/file_facts.hpp"
#include "provider/content/snapshot_resolver.hpp"
#include "provider/content/window_resolver.hpp"
#include "provider/desktop/x11/x11_desktop.hpp"
#include "shared/io/pdf_objects.hpp"
#include "tests/support/temp_dir.hpp"
#include "tests/support/x11_session.hpp"

namespace {

namespace fs = std::filesystem;
namespace p = umf::protocol;
using namespace umf::provider;
using namespace std::chrono_literals;
using Clock = std::chrono::steady_clock;
using namespace umf::test;

// A one-page PDF with correct cross-references, so no viewer has to repair it.
std::string minimal_pdf() {
    const std::string text = "BT /F1 24 Tf 40 100 Td (Hello umf) Tj ET";
    const std::vector<std::string> objects{
        "<< /Type /Catalog /Pages 2 0 R >>",
        "<< /Type /Pages /Kids [3 0 R] /Count 1 >>",
        "<< /Type /Page /Parent 2 0 R /MediaBox [0 0 300 200] /Contents 4 0 R "
        "/Resources << /Font << /F1 5 0 R >> >> >>",
        "<< /Length " + std::to_string(text.size()) + " >>\nstream\n" + text + "\nendstream",
        "<< /Type /Font /Subtype /Type1 /BaseFont /Helvetica >>",
    };
    return umf::io::pdf_from_objects(objects);
}

// Where the windows are put: apart, with bare desktop around them.
constexpr int kPdfX = 40, kPdfY = 40, kPdfW = 520, kPdfH = 400;
constexpr int kTermX = 700, kTermY = 100, kTermW = 400, kTermH = 300;
constexpr double kPdfCentreX = kPdfX + kPdfW / 2.0, kPdfCentreY = kPdfY + kPdfH / 2.0;
constexpr double kTermCentreX = kTermX + kTermW / 2.0, kTermCentreY = kTermY + kTermH / 2.0;
constexpr double kBareX = 1200, kBareY = 700;
const char* const kTermTitle = "notes.txt - umf xterm";

// Xvfb, openbox, mupdf and xterm, started once for all tests.
class X11Session {
public:
    TempDir dir;
    std::string display;
    std::vector<std::string> env;
    std::unique_ptr<Process> xvfb, openbox, mupdf, xterm;
    std::shared_ptr<const X11Desktop> desktop;
    fs::path pdf;
    unsigned long pdf_window = 0, term_window = 0;

    X11Session() {
        auto server = start_xvfb(dir.path / "xvfb.log");
        xvfb = std::move(server.process);
        display = server.display;
        env = environment_with({{"DISPLAY", display},
                                {"HOME", dir.path.string()},
                                {"XDG_CONFIG_HOME", (dir.path / "config").string()},
                                {"XDG_DATA_HOME", (dir.path / "data").string()},
                                {"XDG_CACHE_HOME", (dir.path / "cache").string()}});
        desktop = std::make_shared<const X11Desktop>(display);
        openbox = start_openbox(options("openbox.log"), dir.path / "openbox-ready");
        start_mupdf();
        start_xterm();
    }
    ~X11Session() {
        desktop.reset();  // before the server goes, or Xlib exits the process
        xterm.reset();
        mupdf.reset();
        openbox.reset();
        xvfb.reset();
    }

    Process::Options options(const std::string& log) const { return logged_in(dir.path, env, log); }
    std::string log_of(const std::string& log) const { return read_text(dir.path / log); }

    // mupdf sets no _NET_WM_PID: its PID can only come from the X server.
    void start_mupdf() {
        pdf = dir.path / "report.pdf";
        std::ofstream(pdf, std::ios::binary) << minimal_pdf();
        // openbox announces itself (EWMH) a moment before it manages new
        // windows; one mapped in between stays unmanaged, outside the client
        // list, so the viewer is started again until openbox has it.
        for (int attempt = 0;; ++attempt) {
            mupdf = std::make_unique<Process>(std::vector<std::string>{"mupdf", "report.pdf"}, options("mupdf.log"));
            try {
                pdf_window = wait_for_window([](const WindowInfo& w) { return w.wm_class == "MuPDF"; }, "mupdf",
                                             "mupdf.log", attempt < 2 ? 4s : 20s);
                break;
            } catch (const std::exception&) {
                if (attempt >= 2) throw;
            }
        }
        place(pdf_window, kPdfX, kPdfY, kPdfW, kPdfH, kPdfCentreX, kPdfCentreY);
    }

    void start_xterm() {
        xterm = start_xterm(kTermTitle, "xterm.log");
        const int pid = xterm->pid();
        term_window = wait_for_window([pid](const WindowInfo& w) { return w.pid == pid; }, "xterm", "xterm.log");
        place(term_window, kTermX, kTermY, kTermW, kTermH, kTermCentreX, kTermCentreY);
    }

    std::unique_ptr<Process> start_xterm(const std::string& title, const std::string& log) const {
        return std::make_unique<Process>(std::vector<std::string>{"xterm", "-T", title, "-e", "sleep", "60"},
                                         options(log));
    }

    // Found through the window manager's client list, as the resolver finds
    // windows: xdotool's search, polling the whole tree, now and then missed
    // a window mapped while openbox was still starting.
    template <class Match>
    unsigned long wait_for_window(Match match, const std::string& what, const std::string& log,
                                  std::chrono::milliseconds timeout = 20s) const {
        unsigned long id = 0;
        const bool shown = wait_until(
            [&] {
                for (const auto& w : desktop->windows())
                    if (match(w)) id = w.id;
                return id != 0;
            },
            timeout);
        if (shown) return id;
        std::string seen;
        for (const auto& w : desktop->windows()) seen += " [" + w.wm_class + ": " + w.title + "]";
        std::string tree;
        try {
            tree = run({"xwininfo", "-root", "-tree"}, env);
        } catch (const std::exception& e) {
            tree = e.what();
        }
        throw std::runtime_error(what + " showed no window; windows:" + seen + "; " + what + " said: " + log_of(log) +
                                 "; the tree: " + tree);
    }

    // --sync waits for the move, and would wait forever were the window
    // already there; the centre's window, at about the asked size, tells
    // when it is done. The centre alone is not enough: a new xterm may cover
    // the centre at its own size before the resize reaches it, and a test
    // that snapshots it then sees another size than the window had.
    void place(unsigned long window, int x, int y, int width, int height, double cx, double cy) const {
        const std::string id = std::to_string(window);
        run({"xdotool", "windowsize", id, std::to_string(width), std::to_string(height), "windowmove", id,
             std::to_string(x), std::to_string(y)},
            env);
        // The frame adds up to 40 px across and 60 down; a terminal rounds
        // its size to whole character cells.
        const auto near = [](int got, int asked, int frame) { return got >= asked - 20 && got <= asked + frame; };
        const bool placed = wait_until(
            [&] {
                const auto found = desktop->window_at(cx, cy);
                return found && found->id == window && near(found->rect.width, width, 40) &&
                       near(found->rect.height, height, 60);
            },
            5s);
        if (!placed) throw std::runtime_error("window " + id + " did not move to its place");
    }
};

class X11Test : public ::testing::Test {
protected:
    static void SetUpTestSuite() {
        for (const char* program : {"Xvfb", "openbox", "mupdf", "xterm", "xdotool"})
            if (!find_program(program)) {
                skip_reason_ = std::string(program) +
                               " is not installed (Debian: apt-get install xvfb openbox mupdf xterm xdotool)";
                return;
            }
        try {
            session_ = std::make_unique<X11Session>();
        } catch (const std::exception& e) {
            failure_ = e.what();
        }
    }
    static void TearDownTestSuite() { session_.reset(); }

    void SetUp() override {
        if (!skip_reason_.empty()) GTEST_SKIP() << skip_reason_;
        ASSERT_TRUE(session_) << "the X11 session did not start: " << failure_;
    }

    X11Session& session() { return *session_; }

    WindowResolverOptions window_options(const fs::path& recent_files = {}) {
        WindowResolverOptions options;
        options.documents.home = session().dir.path;
        options.recent_files = recent_files.empty() ? session().dir.path / "no-recent-files.xbel" : recent_files;
        return options;
    }

    // 0 on the bare desktop.
    unsigned long id_at(double x, double y) {
        const auto window = session().desktop->window_at(x, y);
        return window ? window->id : 0;
    }

    static ScreenPoint at(double x, double y) {
        ScreenPoint point;
        point.x = point.root_x = x;
        point.y = point.root_y = y;
        return point;
    }

    static inline std::unique_ptr<X11Session> session_;
    static inline std::string skip_reason_;
    static inline std::string failure_;
};

TEST_F(X11Test, ListsTheShownWindows) {
    const auto& desktop = *session().desktop;
    EXPECT_TRUE(desktop.has_ewmh());
    EXPECT_EQ(desktop.screen(), (WindowRect{0, 0, 1280, 800}));
    std::vector<unsigned long> ids;
    for (const auto& window : desktop.windows()) ids.push_back(window.id);
    EXPECT_NE(std::find(ids.begin(), ids.end(), session().pdf_window), ids.end());
    EXPECT_NE(std::find(ids.begin(), ids.end(), session().term_window), ids.end());
}

TEST_F(X11Test, PdfViewerResolvesToItsFile) {
    const auto window = session().desktop->window_at(kPdfCentreX, kPdfCentreY);
    ASSERT_TRUE(window);
    EXPECT_EQ(window->id, session().pdf_window);
    EXPECT_EQ(window->wm_class, "MuPDF");
    EXPECT_EQ(window->pid, session().mupdf->pid());
    EXPECT_NE(window->title.find("report.pdf"), std::string::npos) << window->title;
    // The frame is included: title bar and borders around the asked size.
    EXPECT_GE(window->rect.width, kPdfW);
    EXPECT_GT(window->rect.height, kPdfH);
    EXPECT_LE(window->rect.width, kPdfW + 40);
    EXPECT_LE(window->rect.height, kPdfH + 60);

    const WindowResolver resolver(session().desktop, window_options());
    for (const Purpose purpose : {Purpose::preview, Purpose::grab}) {
        const auto resolved = resolver.resolve(at(kPdfCentreX, kPdfCentreY), purpose);
        ASSERT_TRUE(resolved);
        EXPECT_EQ(resolved->kind, p::ContentKind::file);
        ASSERT_TRUE(resolved->file);
        EXPECT_TRUE(fs::equivalent(*resolved->file, session().pdf));
        EXPECT_EQ(resolved->name, "report.pdf");
        EXPECT_EQ(resolved->mime, "application/pdf");
        EXPECT_EQ(resolved->title, window->title);
        EXPECT_FALSE(resolved->bytes);
    }
}

TEST_F(X11Test, WindowWithoutDocumentGivesASnapshot) {
    const auto window = session().desktop->window_at(kTermCentreX, kTermCentreY);
    ASSERT_TRUE(window);
    EXPECT_EQ(window->id, session().term_window);
    EXPECT_EQ(window->title, kTermTitle);
    EXPECT_EQ(window->instance, "xterm");
    EXPECT_EQ(window->wm_class, "XTerm");
    EXPECT_EQ(window->pid, session().xterm->pid());

    const WindowResolver resolver(session().desktop, window_options());
    EXPECT_FALSE(resolver.resolve(at(kTermCentreX, kTermCentreY), Purpose::preview));

    const SnapshotResolver snapshots(session().desktop, {}, true);
    const auto preview = snapshots.resolve(at(kTermCentreX, kTermCentreY), Purpose::preview);
    ASSERT_TRUE(preview);
    EXPECT_EQ(preview->kind, p::ContentKind::snapshot);
    EXPECT_EQ(preview->title, std::string(kTermTitle) + " (snapshot)");
    EXPECT_EQ(preview->name, std::string(kTermTitle) + "-snapshot.png");
    EXPECT_EQ(preview->mime, "image/png");
    EXPECT_FALSE(preview->bytes);

    const auto grab = snapshots.resolve(at(kTermCentreX, kTermCentreY), Purpose::grab);
    ASSERT_TRUE(grab && grab->bytes);
    EXPECT_EQ(grab->kind, p::ContentKind::snapshot);
    const QImage image = QImage::fromData(QByteArray::fromStdString(*grab->bytes), "PNG");
    ASSERT_FALSE(image.isNull());
    EXPECT_EQ(image.width(), window->rect.width);
    EXPECT_EQ(image.height(), window->rect.height);
    bool varied = false;
    for (int y = 0; y < image.height() && !varied; ++y)
        for (int x = 0; x < image.width() && !varied; ++x) varied = image.pixel(x, y) != image.pixel(0, 0);
    EXPECT_TRUE(varied) << "the snapshot is one colour";
}

TEST_F(X11Test, RecentFilesNameTheDocumentByTitle) {
    const fs::path notes = session().dir.path / "notes.txt";
    std::ofstream(notes) << "notes";
    const fs::path xbel = session().dir.path / "recently-used.xbel";
    std::ofstream(xbel) << "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n<xbel version=\"1.0\">\n"
                           "<bookmark href=\"file://"
                        << notes.string() << "\" modified=\"2024-01-01T00:00:00Z\"/>\n</xbel>\n";
    const WindowResolver resolver(session().desktop, window_options(xbel));
    const auto resolved = resolver.resolve(at(kTermCentreX, kTermCentreY), Purpose::preview);
    ASSERT_TRUE(resolved);
    EXPECT_EQ(resolved->kind, p::ContentKind::file);
    EXPECT_EQ(resolved->file, notes);
    EXPECT_EQ(resolved->mime, "text/plain");
    EXPECT_EQ(resolved->title, kTermTitle);
}

TEST_F(X11Test, BareDesktopHasNothing) {
    EXPECT_FALSE(session().desktop->window_at(kBareX, kBareY));
    const WindowResolver resolver(session().desktop, window_options());
    EXPECT_FALSE(resolver.resolve(at(kBareX, kBareY), Purpose::preview));
    const SnapshotResolver snapshots(session().desktop, {}, true);
    EXPECT_FALSE(snapshots.resolve(at(kBareX, kBareY), Purpose::preview));
    EXPECT_FALSE(snapshots.resolve(at(kBareX, kBareY), Purpose::grab));
    EXPECT_FALSE(session().desktop->window_at(-5, 10));
    EXPECT_FALSE(session().desktop->window_at(1e9, 1e9));
    EXPECT_FALSE(session().desktop->window_at(std::nan(""), 10));
}

TEST_F(X11Test, OwnAndSkippedWindowsAreLookedThrough) {
    WindowFilter own;
    own.own_pids = {session().xterm->pid()};
    EXPECT_FALSE(session().desktop->window_at(kTermCentreX, kTermCentreY, own));
    EXPECT_TRUE(session().desktop->window_at(kPdfCentreX, kPdfCentreY, own));
    const SnapshotResolver snapshots(session().desktop, own, true);
    EXPECT_FALSE(snapshots.resolve(at(kTermCentreX, kTermCentreY), Purpose::grab));

    WindowResolverOptions options = window_options();
    options.filter.own_pids = {session().mupdf->pid()};
    const WindowResolver resolver(session().desktop, options);
    EXPECT_FALSE(resolver.resolve(at(kPdfCentreX, kPdfCentreY), Purpose::preview));

    WindowFilter by_class;
    by_class.skip_classes = {"MuPDF"};
    EXPECT_FALSE(session().desktop->window_at(kPdfCentreX, kPdfCentreY, by_class));
}

TEST_F(X11Test, DisabledSnapshotsNeverAnswer) {
    const SnapshotResolver snapshots(session().desktop, {}, false);
    EXPECT_FALSE(snapshots.resolve(at(kTermCentreX, kTermCentreY), Purpose::preview));
    EXPECT_FALSE(snapshots.resolve(at(kTermCentreX, kTermCentreY), Purpose::grab));
}

TEST_F(X11Test, ConcurrentAimsAgreeAndStayCheap) {
    const WindowResolver resolver(session().desktop, window_options());
    constexpr int kThreads = 4, kAims = 50;
    std::atomic<int> wrong{0};
    const auto start = Clock::now();
    std::vector<std::thread> threads;
    for (int t = 0; t < kThreads; ++t)
        threads.emplace_back([&] {
            for (int i = 0; i < kAims; ++i) {
                const auto pdf = resolver.resolve(at(kPdfCentreX, kPdfCentreY), Purpose::preview);
                const auto term = resolver.resolve(at(kTermCentreX, kTermCentreY), Purpose::preview);
                if (!pdf || !pdf->file || pdf->file->filename() != "report.pdf" || term) ++wrong;
            }
        });
    for (auto& thread : threads) thread.join();
    const auto per_aim = (Clock::now() - start) / (kThreads * kAims * 2);
    EXPECT_EQ(wrong.load(), 0);
    // Aims come a few times a second per requester.
    EXPECT_LT(per_aim, 20ms);
    std::printf("x11 resolver: %.2f ms per aim (%d threads)\n",
                std::chrono::duration<double, std::milli>(per_aim).count(), kThreads);
}

TEST_F(X11Test, TopMostWindowWinsAndMinimisedOnesAreGone) {
    // Over the PDF viewer's lower right corner, clear of its centre.
    auto cover = session().start_xterm("umf cover", "cover.log");
    const int cover_pid = cover->pid();
    const unsigned long cover_window = session().wait_for_window(
        [cover_pid](const WindowInfo& w) { return w.pid == cover_pid; }, "the covering xterm", "cover.log");
    constexpr double kOverlapX = 480, kOverlapY = 420;
    session().place(cover_window, 400, 350, 200, 150, kOverlapX, kOverlapY);
    EXPECT_EQ(id_at(kOverlapX, kOverlapY), cover_window);
    EXPECT_EQ(id_at(kPdfCentreX, kPdfCentreY), session().pdf_window);

    run({"xdotool", "windowminimize", "--sync", std::to_string(cover_window)}, session().env);
    ASSERT_TRUE(wait_until([&] { return id_at(kOverlapX, kOverlapY) == session().pdf_window; },
                           5s));
    run({"xdotool", "windowactivate", "--sync", std::to_string(cover_window)}, session().env);
    ASSERT_TRUE(wait_until([&] { return id_at(kOverlapX, kOverlapY) == cover_window; }, 5s));

    // A window closing while others look at it (BadWindow mid-query) must
    // not take the process down with Xlib's default error handler.
    std::atomic<bool> done{false};
    std::atomic<int> seen{0};
    std::thread aimer([&] {
        while (!done) {
            const auto window = session().desktop->window_at(kOverlapX, kOverlapY);
            if (window && (window->id == cover_window || window->id == session().pdf_window)) ++seen;
        }
    });
    std::this_thread::sleep_for(50ms);
    cover->stop();
    const bool uncovered = wait_until(
        [&] { return id_at(kOverlapX, kOverlapY) == session().pdf_window; }, 5s);
    done = true;
    aimer.join();
    EXPECT_TRUE(uncovered);
    EXPECT_GT(seen.load(), 0);
}

// No window manager: the root's children in stacking order, no frames.
TEST_F(X11Test, WorksWithoutAWindowManager) {
    TempDir dir;
    const XServer server = start_xvfb(dir.path / "xvfb.log");
    Process::Options options;
    options.cwd = dir.path;
    options.env = environment_with({{"DISPLAY", server.display}, {"HOME", dir.path.string()}});
    options.log = dir.path / "xterm.log";
    const Process xterm({"xterm", "-T", "bare xterm", "-geometry", "40x10+100+120", "-e", "sleep", "60"}, options);
    auto desktop = std::make_shared<const X11Desktop>(server.display);
    EXPECT_FALSE(desktop->has_ewmh());
    std::optional<WindowInfo> window;
    ASSERT_TRUE(wait_until(
        [&] {
            window = desktop->window_at(110, 130);
            return window.has_value();
        },
        10s));
    EXPECT_EQ(window->title, "bare xterm");
    EXPECT_EQ(window->wm_class, "XTerm");
    EXPECT_EQ(window->pid, xterm.pid());
    EXPECT_EQ(window->rect.x, 100);
    EXPECT_EQ(window->rect.y, 120);
    EXPECT_FALSE(desktop->window_at(90, 130));
    const SnapshotResolver snapshots(desktop, {}, true);
    const auto grab = snapshots.resolve(at(110, 130), Purpose::grab);
    ASSERT_TRUE(grab && grab->bytes);
    const QImage image = QImage::fromData(QByteArray::fromStdString(*grab->bytes), "PNG");
    EXPECT_EQ(image.width(), window->rect.width);
    EXPECT_EQ(image.height(), window->rect.height);
    desktop.reset();  // before the server goes
}

TEST(X11DesktopTest, UnknownDisplayThrows) {
    try {
        X11Desktop desktop("/nonexistent/umf-x11-socket:0");
        FAIL() << "opened a display that does not exist";
    } catch (const std::runtime_error& e) {
        EXPECT_NE(std::string(e.what()).find("cannot open the display"), std::string::npos) << e.what();
    }
}

TEST(X11Snapshot, NamesFromTitles) {
    EXPECT_EQ(snapshot_file_name("report.pdf - mupdf"), "report.pdf - mupdf-snapshot.png");
    EXPECT_EQ(snapshot_file_name(""), "screen-snapshot.png");
    EXPECT_EQ(snapshot_file_name("  ..  "), "screen-snapshot.png");
    EXPECT_EQ(snapshot_file_name("a/b\\c: d*?\"<>|\te\n"), "a_b_c_ d______ e-snapshot.png");
    EXPECT_EQ(snapshot_file_name(".hidden"), "hidden-snapshot.png");
    const std::string long_title(300, 'x');
    EXPECT_EQ(snapshot_file_name(long_title), std::string(100, 'x') + "-snapshot.png");
    // Cut between UTF-8 sequences, never inside one.
    std::string accents;
    for (int i = 0; i < 60; ++i) accents += "\xC3\xA9";
    EXPECT_EQ(snapshot_file_name(accents), accents.substr(0, 100) + "-snapshot.png");
}

TEST(X11Snapshot, RectanglesStayOnScreenAndWithinTheCap) {
    const WindowRect screen{0, 0, 1920, 1080};
    EXPECT_EQ(snapshot_rect({100, 100, 400, 300}, screen, 200, 200), (WindowRect{100, 100, 400, 300}));
    EXPECT_EQ(snapshot_rect({-50, -20, 400, 300}, screen, 10, 10), (WindowRect{0, 0, 350, 280}));
    EXPECT_EQ(snapshot_rect({1800, 1000, 400, 300}, screen, 1850, 1050), (WindowRect{1800, 1000, 120, 80}));
    EXPECT_TRUE(snapshot_rect({3000, 0, 100, 100}, screen, 3010, 10).empty());
    // Bigger than the cap: cut around the point, kept within the window.
    EXPECT_EQ(snapshot_rect({0, 0, 1920, 1080}, screen, 1000, 500, 200), (WindowRect{900, 400, 200, 200}));
    EXPECT_EQ(snapshot_rect({0, 0, 1920, 1080}, screen, 10, 1075, 200), (WindowRect{0, 880, 200, 200}));
}

TEST(X11Snapshot, EncodesPng) {
    Capture capture{3, 2, {0xffff0000u, 0xff00ff00u, 0xff0000ffu, 0xffffffffu, 0xff000000u, 0xff808080u}};
    const std::string png = encode_png(capture);
    ASSERT_GT(png.size(), 8u);
    EXPECT_EQ(png.substr(1, 3), "PNG");
    const QImage image = QImage::fromData(QByteArray::fromStdString(png), "PNG");
    ASSERT_EQ(image.size(), QSize(3, 2));
    EXPECT_EQ(image.pixel(0, 0), 0xffff0000u);
    EXPECT_EQ(image.pixel(2, 1), 0xff808080u);
    EXPECT_THROW(encode_png(Capture{}), std::runtime_error);
    EXPECT_THROW(encode_png(Capture{2, 2, {1, 2, 3}}), std::runtime_error);
}

TEST(X11Window, MimeTypesByExtension) {
    EXPECT_EQ(mime_for("/a/report.PDF"), "application/pdf");
    EXPECT_EQ(mime_for("photo.jpeg"), "image/jpeg");
    EXPECT_EQ(mime_for("sheet.xlsx"), "application/vnd.openxmlformats-officedocument.spreadsheetml.sheet");
    EXPECT_EQ(mime_for("clip.mp4"), "video/mp4");
    EXPECT_EQ(mime_for("Makefile"), "application/octet-stream");
    EXPECT_EQ(mime_for("archive.tar.xz"), "application/octet-stream");
}

TEST(X11Window, RectanglesContainTheirPixels) {
    const WindowRect rect{10, 20, 30, 40};
    EXPECT_TRUE(rect.contains(10, 20));
    EXPECT_TRUE(rect.contains(39.99, 59.99));
    EXPECT_FALSE(rect.contains(40, 30));
    EXPECT_FALSE(rect.contains(9.99, 30));
    EXPECT_FALSE(rect.contains(20, 60));
}

}  // namespace

#endif  // UMF_PROVIDER_TESTS
