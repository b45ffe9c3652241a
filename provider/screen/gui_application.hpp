// The provider's QGuiApplication. Painting text (board titles) needs one even
// when nothing is shown, so compose and the headless provider make one on
// Qt's "offscreen" platform, which needs no display.
#pragma once

#include <QGuiApplication>
#include <memory>

namespace umf::provider {

// With `headless`, or when neither DISPLAY nor WAYLAND_DISPLAY is set, Qt is
// told to use the offscreen platform, unless the user chose a platform with
// QT_QPA_PLATFORM. argc and argv must outlive the application (Qt keeps
// references to them).
std::unique_ptr<QGuiApplication> make_gui_application(int& argc, char** argv, bool headless);

}  // namespace umf::provider
