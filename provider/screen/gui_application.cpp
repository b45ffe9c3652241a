#include "provider/screen/gui_application.hpp"

#include <QtGlobal>

namespace umf::provider {

std::unique_ptr<QGuiApplication> make_gui_application(int& argc, char** argv, bool headless) {
    const bool no_display = qEnvironmentVariableIsEmpty("DISPLAY") && qEnvironmentVariableIsEmpty("WAYLAND_DISPLAY");
    // Without a display the default platform (xcb) would abort the process.
    if ((headless || no_display) && !qEnvironmentVariableIsSet("QT_QPA_PLATFORM"))
        qputenv("QT_QPA_PLATFORM", "offscreen");
    return std::make_unique<QGuiApplication>(argc, argv);
}

}  // namespace umf::provider
