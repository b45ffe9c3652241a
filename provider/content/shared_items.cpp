#include "content/shared_items.hpp"

#include <stdexcept>

#include "content/board_resolver.hpp"

namespace umf::provider {


int SharedItems::add(SharedItem item) {
    if (item.title.empty()) item.title = item.file ? item.file->filename().string() : item.url.value_or("");
    if (item.file.has_value() == item.url.has_value())
        throw std::invalid_argument("a shared item is either a file or a URL");
    if (item.file) {
        std::error_code ec;
        *item.file = std::filesystem::absolute(*item.file, ec);
        if (ec || !std::filesystem::is_regular_file(*item.file, ec))
            throw std::invalid_argument(item.file->string() + " is not a readable regular file");
    }
    if (item.url && (!protocol::is_http_url(*item.url) || item.url->size() > protocol::kMaxUrlBytes))
        throw std::invalid_argument("a shared URL starts with http:// or https:// and has no spaces");
    if (item.rect.width <= 0 || item.rect.height <= 0)
        throw std::invalid_argument("a shared item's region needs a positive width and height");
    std::lock_guard lock(mutex_);
    if (items_.size() >= kMaxItems) throw std::length_error("too many shared items; remove some first");
    item.id = next_id_++;
    items_.push_back(std::move(item));
    return items_.back().id;
}

bool SharedItems::remove(int id) {
    std::lock_guard lock(mutex_);
    for (auto it = items_.begin(); it != items_.end(); ++it)
        if (it->id == id) {
            items_.erase(it);
            return true;
        }
    return false;
}

std::vector<SharedItem> SharedItems::items() const {
    std::lock_guard lock(mutex_);
    return items_;
}

std::optional<Resolved> SharedItems::resolve(const ScreenPoint& point, Purpose) const {
    std::lock_guard lock(mutex_);
    for (auto it = items_.rbegin(); it != items_.rend(); ++it)
        if (it->screen == point.screen && it->rect.contains(point.x, point.y))
            return resolved_item(it->title, it->file, it->url);
    return std::nullopt;
}

}  // namespace umf::provider
