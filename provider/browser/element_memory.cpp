#include "provider/browser/element_memory.hpp"

#include <cmath>

namespace umf::provider {

std::optional<WindowRect> element_screen_rect(const nlohmann::json& element) {
    if (!element.is_object()) return std::nullopt;
    const auto found = element.find("screen_rect");
    if (found == element.end() || !found->is_array() || found->size() != 4) return std::nullopt;
    double v[4];
    for (int i = 0; i < 4; ++i) {
        if (!(*found)[i].is_number()) return std::nullopt;
        v[i] = (*found)[i].get<double>();
        // Beyond any screen's coordinates (and int's range): not a place.
        if (!std::isfinite(v[i]) || std::abs(v[i]) > 1e6) return std::nullopt;
    }
    WindowRect rect{static_cast<int>(std::floor(v[0])), static_cast<int>(std::floor(v[1])),
                    static_cast<int>(std::ceil(v[2])), static_cast<int>(std::ceil(v[3]))};
    if (rect.empty()) return std::nullopt;
    return rect;
}

void ElementMemory::remember(const BrowserMatch& window, const nlohmann::json& element, Clock::time_point now) {
    const auto rect = element_screen_rect(element);
    const std::lock_guard lock(mutex_);
    if (!rect || element.value("kind", "") == "outside") {
        kept_.reset();
        return;
    }
    kept_ = Kept{window.connection, window.window.id, window.window.tab.id, window.window.tab.url, *rect, now, element};
}

std::optional<nlohmann::json> ElementMemory::recall(const BrowserMatch& window, double x, double y,
                                                    Clock::time_point now) const {
    const std::lock_guard lock(mutex_);
    if (!kept_ || kept_->connection != window.connection || kept_->window != window.window.id ||
        kept_->tab != window.window.tab.id || kept_->url != window.window.tab.url || now - kept_->at > keep_ ||
        now < kept_->at || !kept_->rect.contains(x, y))
        return std::nullopt;
    return kept_->element;
}

}  // namespace umf::provider
