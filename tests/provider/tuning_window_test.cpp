// The tuning window, its preset store, the palette taken from an image and
// the tray menu, on the offscreen platform. UMF_PROVIDER_TUNING as well:
// this file is globbed into umf_tests before CMake builds provider/tuning/
// (and links Qt6::Widgets), and must compile to nothing until it does.
#if defined(UMF_PROVIDER_TESTS) && defined(UMF_PROVIDER_TUNING)

#include <gtest/gtest.h>

#include <QAction>
#include <QApplication>
#include <QComboBox>
#include <QMenu>
#include <QPainter>
#include <QPushButton>
#include <QSlider>
#include <QSystemTrayIcon>
#include <filesystem>
#include <fstream>

#include "provider/tuning/palette_from_image.hpp"
#include "provider/tuning/preset_store.hpp"
#include "provider/tuning/slider_spin.hpp"
#include "provider/tuning/tray_menu.hpp"
#include "provider/tuning/tuning_window.hpp"
#include "tests/support/temp_dir.hpp"

namespace {

namespace fs = std::filesystem;
using namespace umf::provider;
using umf::overlay::Preset;
using umf::test::TempDir;

// Widgets need a QApplication, not the QGuiApplication gui_test_app.hpp
// makes; when another test made that one first, the widget tests skip.
bool ensure_widget_application() {
    if (!QCoreApplication::instance()) {
        static int argc = 1;
        static char name[] = "umf_tests";
        static char* argv[] = {name, nullptr};
        qputenv("QT_QPA_PLATFORM", "offscreen");
        new QApplication(argc, argv);  // lives as long as the process
    }
    return qobject_cast<QApplication*>(QCoreApplication::instance()) != nullptr;
}

#define REQUIRE_WIDGETS()                                                                                  \
    if (!ensure_widget_application())                                                                      \
    GTEST_SKIP() << "a QGuiApplication, not a QApplication, exists already (tests/provider/gui_test_app.hpp); " \
                    "widgets cannot be made"

Preset mine(const std::string& name) {
    Preset p;
    p.name = name;
    p.opacity_min = 0.05;
    p.opacity_max = 0.2;
    p.palette = {"#102030", "#e0d0c0"};
    return p;
}

template <class F>
std::string refusal(F&& f) {
    try {
        f();
    } catch (const PresetStoreError& e) {
        return e.what();
    }
    return "(not refused)";
}

// ---- PresetStore ----

TEST(PresetStore, MissingFileIsJustTheBuiltIns) {
    TempDir dir;
    PresetStore store((dir.path / "umf" / "presets.json").string());
    EXPECT_EQ(store.list(), umf::overlay::built_in_presets());
    EXPECT_FALSE(fs::exists(dir.path / "umf" / "presets.json"));
}

TEST(PresetStore, RoundTripThroughTheFile) {
    TempDir dir;
    const std::string path = (dir.path / "umf" / "presets.json").string();
    Preset subtle = umf::overlay::built_in_presets().front();
    subtle.opacity_max = 0.3;
    {
        PresetStore store(path);
        store.save(mine("desk"));
        store.save(subtle);
    }
    PresetStore again(path);
    EXPECT_EQ(again.get("desk"), mine("desk"));
    EXPECT_EQ(again.get("subtle"), subtle);
    EXPECT_TRUE(again.is_overridden("subtle"));
    EXPECT_EQ(again.built_in("subtle"), umf::overlay::built_in_presets().front());
    const auto list = again.list();
    ASSERT_EQ(list.size(), umf::overlay::built_in_presets().size() + 1);
    EXPECT_EQ(list.front(), subtle);  // the override in the built-in's place
    EXPECT_EQ(list.back().name, "desk");
    EXPECT_EQ(umf::overlay::load_presets(path).size(), 2u);

    again.rename("desk", "office");
    again.reset("subtle");
    PresetStore third(path);
    EXPECT_FALSE(third.contains("desk"));
    EXPECT_EQ(third.get("office").opacity_max, 0.2);
    EXPECT_EQ(third.get("subtle"), umf::overlay::built_in_presets().front());
    third.remove("office");
    EXPECT_EQ(PresetStore(path).list(), umf::overlay::built_in_presets());
}

TEST(PresetStore, Refusals) {
    TempDir dir;
    const std::string path = (dir.path / "presets.json").string();
    PresetStore store(path);
    store.save(mine("desk"));
    store.save(mine("tv"));

    Preset bad = mine("broken");
    bad.opacity_min = 0.9;
    EXPECT_NE(refusal([&] { store.save(bad); }).find("\"broken\""), std::string::npos);
    EXPECT_NE(refusal([&] { store.save(bad); }).find("opacity_min"), std::string::npos);
    EXPECT_NE(refusal([&] { store.get("nope"); }).find("\"nope\""), std::string::npos);
    EXPECT_NE(refusal([&] { store.built_in("desk"); }).find("not a built-in"), std::string::npos);
    EXPECT_NE(refusal([&] { store.rename("subtle", "x"); }).find("built-in"), std::string::npos);
    EXPECT_NE(refusal([&] { store.rename("nope", "x"); }).find("no such"), std::string::npos);
    EXPECT_NE(refusal([&] { store.rename("desk", "tv"); }).find("taken"), std::string::npos);
    EXPECT_NE(refusal([&] { store.rename("desk", "kiosk"); }).find("taken"), std::string::npos);
    EXPECT_NE(refusal([&] { store.rename("desk", ""); }).find("name"), std::string::npos);
    EXPECT_NE(refusal([&] { store.remove("balanced"); }).find("built-in"), std::string::npos);
    EXPECT_NE(refusal([&] { store.remove("nope"); }).find("no such"), std::string::npos);
    EXPECT_NE(refusal([&] { store.reset("desk"); }).find("not a built-in"), std::string::npos);
    EXPECT_NE(refusal([&] { store.reset("balanced"); }).find("no changes"), std::string::npos);
    // Nothing refused reached the file.
    const auto saved = umf::overlay::load_presets(path);
    ASSERT_EQ(saved.size(), 2u);
    EXPECT_EQ(saved[0], mine("desk"));
    EXPECT_EQ(saved[1], mine("tv"));
}

TEST(PresetStore, BrokenFileIsReportedNotOverwritten) {
    TempDir dir;
    const std::string path = (dir.path / "presets.json").string();
    std::ofstream(path) << "[{\"name\": \"x\", \"opacity_max\": 7}]";
    EXPECT_THROW(PresetStore{path}, umf::overlay::PresetError);
}

TEST(PresetStore, FailedWriteKeepsTheStore) {
    TempDir dir;
    std::ofstream(dir.path / "config") << "a file where the folder should be";
    PresetStore store((dir.path / "config" / "presets.json").string());
    EXPECT_THROW(store.save(mine("desk")), PresetStoreError);
    EXPECT_FALSE(store.contains("desk"));
}

TEST(PresetStore, DefaultPathFollowsXdg) {
    const char* old = std::getenv("XDG_CONFIG_HOME");
    const std::string saved = old ? old : "";
    setenv("XDG_CONFIG_HOME", "/somewhere/config", 1);
    EXPECT_EQ(PresetStore::default_path(), "/somewhere/config/umf/presets.json");
    if (old) setenv("XDG_CONFIG_HOME", saved.c_str(), 1); else unsetenv("XDG_CONFIG_HOME");
}

// ---- palette_from_image ----

TEST(PaletteFromImage, TwoColoursComeBackDarkToLight) {
    QImage img(200, 100, QImage::Format_RGB32);
    img.fill(QColor("#f0c814"));
    QPainter(&img).fillRect(0, 0, 60, 100, QColor("#1e3c78"));
    EXPECT_EQ(palette_from_image(img, 2), (std::vector<std::string>{"#1e3c78", "#f0c814"}));
    // Asked for more than there are: only what there is.
    EXPECT_EQ(palette_from_image(img, 5), (std::vector<std::string>{"#1e3c78", "#f0c814"}));
    EXPECT_TRUE(palette_from_image(QImage(), 2).empty());
    EXPECT_TRUE(palette_from_image(img, 0).empty());
}

TEST(PaletteFromImage, DistinctBeatsCommon) {
    // Mostly two near greys, a little red: the red is one of the two.
    QImage img(100, 100, QImage::Format_RGB32);
    img.fill(QColor("#808080"));
    QPainter p(&img);
    p.fillRect(0, 0, 100, 45, QColor("#848484"));
    p.fillRect(0, 90, 100, 10, QColor("#ff0000"));
    p.end();
    const auto colours = palette_from_image(img, 2);
    ASSERT_EQ(colours.size(), 2u);
    EXPECT_EQ(colours[0], "#ff0000");  // luma of pure red is below mid grey
}

// ---- TuningWindow ----

QImage sample_screen() {
    QImage img(960, 540, QImage::Format_RGB32);
    img.fill(QColor("#d0d8e0"));
    QPainter p(&img);
    p.fillRect(100, 100, 400, 300, QColor("#203040"));
    return img;
}

struct WindowFixture {
    TempDir dir;
    PresetStore store{(dir.path / "presets.json").string()};
    std::vector<Preset> emitted;
    TuningWindow window{store, "balanced", [this](const Preset& p) { emitted.push_back(p); }, sample_screen()};
    SliderSpin* slider(const char* name) { return window.findChild<SliderSpin*>(name); }
    QPushButton* button(const char* name) { return window.findChild<QPushButton*>(name); }
};

TEST(TuningWindow, OpacitySliderEmitsTheNewValue) {
    REQUIRE_WIDGETS();
    WindowFixture f;
    ASSERT_FALSE(f.emitted.empty());  // the initial preset, for the overlay to show
    EXPECT_EQ(f.emitted.back().name, "balanced");
    f.emitted.clear();
    SliderSpin* max = f.slider("opacity_max");
    ASSERT_NE(max, nullptr);
    max->slider()->setValue(55);
    ASSERT_EQ(f.emitted.size(), 1u);
    EXPECT_DOUBLE_EQ(f.emitted.back().opacity_max, 0.55);
    EXPECT_DOUBLE_EQ(f.window.preset().opacity_max, 0.55);
    EXPECT_EQ(f.emitted.back().opacity_min, 0.1);
}

TEST(TuningWindow, MinAboveMaxIsPrevented) {
    REQUIRE_WIDGETS();
    WindowFixture f;
    f.slider("opacity_min")->slider()->setValue(80);
    EXPECT_DOUBLE_EQ(f.emitted.back().opacity_min, 0.8);
    EXPECT_DOUBLE_EQ(f.emitted.back().opacity_max, 0.8);
    EXPECT_DOUBLE_EQ(f.slider("opacity_max")->value(), 0.8);
    f.slider("opacity_max")->slider()->setValue(20);
    EXPECT_DOUBLE_EQ(f.emitted.back().opacity_min, 0.2);
    for (const auto& p : f.emitted) EXPECT_LE(p.opacity_min, p.opacity_max);
}

TEST(TuningWindow, PeriodStepsOverTheGapAboveStatic) {
    REQUIRE_WIDGETS();
    WindowFixture f;
    f.slider("period")->slider()->setValue(2);  // 0.2 s from 1.5 s: down to static
    EXPECT_EQ(f.window.preset().period_s, 0.0);
    f.slider("period")->slider()->setValue(1);  // up from static: the fastest allowed
    EXPECT_EQ(f.window.preset().period_s, umf::overlay::kMinPeriodS);
    for (const auto& p : f.emitted) EXPECT_EQ(umf::overlay::describe_invalid(p), "");
}

TEST(TuningWindow, SaveWritesTheUserFileAndANewWindowSeesIt) {
    REQUIRE_WIDGETS();
    WindowFixture f;
    f.slider("module_px")->slider()->setValue(44);
    ASSERT_TRUE(f.window.save());
    EXPECT_EQ(umf::overlay::load_presets(f.store.path()).at(0).module_px, 44.0);
    PresetStore fresh(f.store.path());
    TuningWindow other(fresh, "balanced", {}, sample_screen());
    EXPECT_EQ(other.preset().module_px, 44.0);
    EXPECT_TRUE(other.findChild<QPushButton*>("reset")->isEnabled());
    EXPECT_FALSE(other.findChild<QPushButton*>("delete")->isEnabled());
}

TEST(TuningWindow, SaveAsRenameDeleteReset) {
    REQUIRE_WIDGETS();
    WindowFixture f;
    f.slider("blur")->slider()->setValue(30);
    EXPECT_FALSE(f.window.save_as("kiosk"));  // taken
    EXPECT_NE(f.window.message().indexOf("kiosk"), -1);
    ASSERT_TRUE(f.window.save_as("desk"));
    EXPECT_EQ(f.window.preset().name, "desk");
    EXPECT_EQ(f.store.get("desk").blur, 0.3);
    EXPECT_EQ(f.store.get("balanced"), f.store.built_in("balanced"));  // the built-in untouched
    EXPECT_TRUE(f.button("rename")->isEnabled());

    EXPECT_FALSE(f.window.rename_to("subtle"));
    ASSERT_TRUE(f.window.rename_to("office"));
    EXPECT_FALSE(f.store.contains("desk"));
    EXPECT_EQ(f.store.get("office").blur, 0.3);
    auto* chooser = f.window.findChild<QComboBox*>("chooser");
    EXPECT_EQ(chooser->currentData().toString(), "office");

    ASSERT_TRUE(f.window.remove());
    EXPECT_FALSE(f.store.contains("office"));
    EXPECT_EQ(chooser->findData("office"), -1);
    EXPECT_EQ(f.window.preset().name, f.store.list().front().name);

    f.window.choose("visible");
    EXPECT_FALSE(f.window.remove());  // built-in
    EXPECT_FALSE(f.window.reset());   // nothing to drop
    f.slider("opacity_max")->slider()->setValue(70);
    ASSERT_TRUE(f.window.save());
    EXPECT_TRUE(f.store.is_overridden("visible"));
    ASSERT_TRUE(f.window.reset());
    EXPECT_FALSE(f.store.is_overridden("visible"));
    EXPECT_EQ(f.window.preset(), f.store.built_in("visible"));
    EXPECT_DOUBLE_EQ(f.slider("opacity_max")->value(), 0.5);
}

TEST(TuningWindow, PaletteFromImageIsAppliedAndOneColourIsExplained) {
    REQUIRE_WIDGETS();
    WindowFixture f;
    f.window.palette_from(sample_screen());
    EXPECT_EQ(f.window.preset().palette, (std::vector<std::string>{"#203040", "#d0d8e0"}));
    EXPECT_EQ(f.emitted.back().palette, f.window.preset().palette);
    QImage flat(10, 10, QImage::Format_RGB32);
    flat.fill(Qt::red);
    f.window.palette_from(flat);
    EXPECT_NE(f.window.message().indexOf("too few"), -1);
    EXPECT_EQ(f.window.preset().palette.size(), 2u);
}

TEST(TuningWindow, RendersSomethingWorthLookingAt) {
    REQUIRE_WIDGETS();
    WindowFixture f;
    f.window.palette_from(sample_screen());
    f.window.resize(f.window.sizeHint());
    const QImage shot = f.window.grab().toImage();
    ASSERT_FALSE(shot.isNull());
    shot.save("/tmp/umf_tuning_window.png");
    const QRgb first = shot.pixel(0, 0);
    bool varied = false;
    for (int y = 0; y < shot.height() && !varied; y += 3)
        for (int x = 0; x < shot.width() && !varied; x += 3) varied = shot.pixel(x, y) != first;
    EXPECT_TRUE(varied);
}

// ---- TrayMenu ----

TEST(TrayMenu, ActionsInOrderAndCallbacks) {
    REQUIRE_WIDGETS();
    std::vector<std::string> calls;
    TrayCallbacks cb;
    cb.overlay_toggled = [&](bool on) { calls.push_back(on ? "on" : "off"); };
    cb.preset_chosen = [&](const std::string& p) { calls.push_back("preset " + p); };
    cb.tune = [&] { calls.push_back("tune"); };
    cb.pairing_qr = [&] { calls.push_back("qr"); };
    cb.quit = [&] { calls.push_back("quit"); };
    TrayMenu tray({"subtle", "balanced", "desk"}, "balanced", true, cb);
    (void)TrayMenu::available();  // either answer is fine; it must not crash

    QStringList texts;
    for (QAction* a : tray.menu()->actions())
        if (!a->isSeparator()) texts << a->text();
    EXPECT_EQ(texts, (QStringList{"Overlay on", "Preset", "Tune…", "Pairing QR code…", "Quit"}));
    QAction* overlay = tray.menu()->actions().at(0);
    EXPECT_TRUE(overlay->isCheckable());
    EXPECT_TRUE(overlay->isChecked());

    QMenu* presets = tray.menu()->actions().at(1)->menu();
    ASSERT_NE(presets, nullptr);
    QStringList names;
    for (QAction* a : presets->actions()) {
        names << a->text();
        EXPECT_TRUE(a->isCheckable());
    }
    EXPECT_EQ(names, (QStringList{"subtle", "balanced", "desk"}));
    EXPECT_TRUE(presets->actions().at(1)->isChecked());

    presets->actions().at(2)->trigger();
    EXPECT_TRUE(presets->actions().at(2)->isChecked());
    EXPECT_FALSE(presets->actions().at(1)->isChecked());
    overlay->trigger();
    for (QAction* a : tray.menu()->actions())
        if (a->text() == "Tune…" || a->text() == "Pairing QR code…" || a->text() == "Quit") a->trigger();
    EXPECT_EQ(calls, (std::vector<std::string>{"preset desk", "off", "tune", "qr", "quit"}));

    tray.set_overlay_on(true);  // quietly
    tray.set_presets({"kiosk"}, "kiosk");
    EXPECT_EQ(calls.size(), 5u);
    ASSERT_EQ(presets->actions().size(), 1);
    EXPECT_TRUE(presets->actions().at(0)->isChecked());
    EXPECT_FALSE(tray.tray_icon()->icon().isNull());
}

TEST(TrayMenu, ADesktopWithoutAFieldSaysWhatWorks) {
    REQUIRE_WIDGETS();
    std::vector<std::string> calls;
    TrayCallbacks cb;
    cb.pairing_qr = [&] { calls.push_back("qr"); };
    cb.quit = [&] { calls.push_back("quit"); };
    const std::string status = "No field on this desktop (wayland (no backend)): boards, shares and puts work.";
    TrayMenu tray(cb, status);
    QStringList texts;
    for (QAction* a : tray.menu()->actions())
        if (!a->isSeparator()) texts << a->text();
    EXPECT_EQ(texts, (QStringList{QString::fromStdString(status), "Pairing QR code…", "Quit"}));
    EXPECT_FALSE(tray.menu()->actions().at(0)->isEnabled()) << "the status is to read, not to click";
    EXPECT_TRUE(tray.tray_icon()->toolTip().contains("No field on this desktop"));
    for (QAction* a : tray.menu()->actions())
        if (a->isEnabled() && !a->isSeparator()) a->trigger();
    EXPECT_EQ(calls, (std::vector<std::string>{"qr", "quit"}));
    // Nothing to follow without an overlay, and nothing breaks.
    tray.set_overlay_on(true);
    tray.set_presets({"kiosk"}, "kiosk");
}

// "Start at login" is there when the provider can write the autostart entry;
// it says the entry's state without calling back, and calls back when
// switched.
TEST(TrayMenu, StartAtLoginIsOfferedAndSwitched) {
    REQUIRE_WIDGETS();
    std::vector<bool> calls;
    TrayCallbacks cb;
    cb.start_at_login = [&](bool on) { calls.push_back(on); };
    TrayMenu tray({"balanced"}, "balanced", true, cb);
    QAction* start = nullptr;
    for (QAction* a : tray.menu()->actions())
        if (a->text() == "Start at login") start = a;
    ASSERT_NE(start, nullptr);
    EXPECT_TRUE(start->isCheckable());
    EXPECT_FALSE(start->isChecked());
    tray.set_start_at_login(true);
    EXPECT_TRUE(start->isChecked());
    EXPECT_TRUE(calls.empty()) << "following the entry's state is not a switch";
    start->trigger();
    start->trigger();
    EXPECT_EQ(calls, (std::vector<bool>{false, true}));
    EXPECT_EQ(tray.menu()->actions().back()->text(), "Quit");
}

// The desktop's abilities change while the provider runs (GNOME's extension
// stopped, or came back): the tray says what works now.
TEST(TrayMenu, TheStatusFollowsTheDesktop) {
    REQUIRE_WIDGETS();
    TrayMenu tray({"balanced", "kiosk"}, "balanced", true, {});
    EXPECT_EQ(tray.tray_icon()->toolTip(), "umf provider");
    EXPECT_EQ(tray.menu()->actions().at(0)->text(), "Overlay on");
    const auto texts = [&] {
        QStringList out;
        for (QAction* a : tray.menu()->actions()) out << (a->isSeparator() ? QString("--") : a->text());
        return out;
    };
    const QStringList plain = texts();
    tray.set_status("No field on this desktop (gnome): boards, shares and puts work.");
    EXPECT_EQ(tray.menu()->actions().at(0)->text(), "No field on this desktop (gnome): boards, shares and puts work.");
    EXPECT_FALSE(tray.menu()->actions().at(0)->isEnabled());
    EXPECT_TRUE(tray.menu()->actions().at(1)->isSeparator());
    EXPECT_EQ(tray.tray_icon()->toolTip(), "umf provider: No field on this desktop (gnome): boards, shares and puts work.");
    tray.set_status("The field is shown on gnome.");
    EXPECT_EQ(tray.menu()->actions().at(0)->text(), "The field is shown on gnome.");
    EXPECT_EQ(texts().size(), plain.size() + 2) << "one line and its separator, not two";
    EXPECT_TRUE(tray.tray_icon()->toolTip().endsWith("The field is shown on gnome."));
    tray.set_status("");
    EXPECT_EQ(texts(), plain);
    EXPECT_EQ(tray.tray_icon()->toolTip(), "umf provider");
}

}  // namespace

#endif  // UMF_PROVIDER_TESTS && UMF_PROVIDER_TUNING
