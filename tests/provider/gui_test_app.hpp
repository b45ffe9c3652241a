// The QApplication (widgets need one; painting needs at least a
// QGuiApplication) the provider's painting and tuning tests need (text needs fonts,
// fonts need the application). Made once, on the offscreen platform, and
// never destroyed: tearing it down during static destruction would race Qt's
// own global objects.
#pragma once

#include <QApplication>

namespace umf::test {

inline void ensure_gui_application() {
    if (QCoreApplication::instance()) return;
    static int argc = 1;
    static char name[] = "umf_tests";
    static char* argv[] = {name, nullptr};
    qputenv("QT_QPA_PLATFORM", "offscreen");
    new QApplication(argc, argv);  // lives as long as the process
}

}  // namespace umf::test
