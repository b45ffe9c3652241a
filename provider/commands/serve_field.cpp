#include "commands/serve_field.hpp"

#include <QCoreApplication>
#include <QMetaObject>
#include <iostream>
#include <stdexcept>

#include "field_overlay/overlay_manager.hpp"
#include "screen/board_window.hpp"
#include "screen/desktop_layout.hpp"
#include "screen/screen_field.hpp"
#include "server/service.hpp"

namespace umf::provider {

FieldShown show_own_field(const FieldShowing& s) {
    if (!s.fields.own())  // --shipped-field: a new seed is for the next start without it
        return {screen_field_for(s.width, s.height, s.module_px, s.fields).field.id, false};
    FieldSource fresh = own_field_source(s.config_dir);
    const bool changed = fresh.seed() != s.fields.seed();
    if (changed) s.fields = std::move(fresh);
    if (s.overlay) {
        if (changed) s.overlay->set_fields(s.fields);  // its screens-changed callback tells the service
        return {s.overlay->layout() ? s.overlay->layout()->field.id : std::string(), changed};
    }
    const ScreenField field = screen_field_for(s.width, s.height, s.module_px, s.fields);
    if (changed) {
        if (s.board_window) s.board_window->show_field(s.board_image, field);
        s.service.set_screens(lay_out_desktop({{s.screen_name, 0, 0, s.width, s.height, s.module_px}}, s.fields));
        std::cout << "field: " << field.field.id << " (this screen's own, with a new seed)\n" << std::flush;
    }
    return {field.field.id, changed};
}

FieldShown show_own_field_from_any_thread(const FieldShowing& showing) {
    if (!showing.overlay && !showing.board_window) return show_own_field(showing);
    FieldShown shown;
    std::string error;
    QMetaObject::invokeMethod(
        qApp,
        [&] {
            try {
                shown = show_own_field(showing);
            } catch (const std::exception& e) {
                error = e.what();
            }
        },
        Qt::BlockingQueuedConnection);
    if (!error.empty()) throw std::runtime_error(error);
    return shown;
}

}  // namespace umf::provider
