#include "provider/commands/serve_field.hpp"

#include <QCoreApplication>
#include <QMetaObject>
#include <iostream>
#include <stdexcept>

#include "provider/field_overlay/overlay_manager.hpp"
#include "provider/screen/board_window.hpp"
#include "provider/screen/desktop_layout.hpp"
#include "provider/service/service.hpp"

namespace umf::provider {

FieldShown show_own_field(const FieldShowing& s) {
    bool changed = false;
    if (s.fields.own()) {  // --shipped-field: a new seed is for the next start without it
        FieldSource fresh = own_field_source(s.config_dir);
        changed = fresh.seed() != s.fields.seed();
        if (changed) s.fields = std::move(fresh);
    }
    if (s.overlay) {
        if (changed) s.overlay->set_fields(s.fields);  // its screens-changed callback tells the service
        return {s.overlay->layout() ? s.overlay->layout()->field.id : std::string(), changed};
    }
    // The one screen's field as the service has it: laid out anew only for a new seed.
    if (!changed) return {s.service.screens()->field.definition.id, false};
    const DesktopLayout layout = lay_out_desktop({{s.screen_name, 0, 0, s.width, s.height, s.module_px}}, s.fields);
    if (s.board_window) s.board_window->show_field(s.board_image, layout.screens.at(0).field);
    s.service.set_screens(layout);
    std::cout << "field: " << layout.field.id << " (this screen's own, with a new seed)\n" << std::flush;
    return {layout.field.id, true};
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
