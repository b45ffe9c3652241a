#include "provider/content/shared_items.hpp"

#include <algorithm>
#include <stdexcept>

#include "provider/content/board_resolver.hpp"

namespace umf::provider {

void SharedItems::check(SharedItem& item) {
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
}

int SharedItems::add(SharedItem item) {
    check(item);
    std::lock_guard lock(mutex_);
    if (items_.size() >= kMaxItems) throw std::length_error("too many shared items; remove some first");
    item.id = next_id_++;
    items_.push_back(std::move(item));
    if (listener_) listener_(items_);
    return items_.back().id;
}

int SharedItems::restore(const std::vector<SharedItem>& kept) {
    std::lock_guard lock(mutex_);
    int restored = 0;
    for (SharedItem item : kept) {
        try {
            check(item);
        } catch (const std::invalid_argument&) {
            continue;
        }
        if (items_.size() >= kMaxItems || item.id <= 0) continue;
        bool taken = false;
        for (const auto& existing : items_) taken = taken || existing.id == item.id;
        if (taken) continue;
        next_id_ = std::max(next_id_, item.id + 1);
        items_.push_back(std::move(item));
        ++restored;
    }
    if (listener_ && restored > 0) listener_(items_);
    return restored;
}

void SharedItems::on_change(std::function<void(const std::vector<SharedItem>&)> listener) {
    std::lock_guard lock(mutex_);
    listener_ = std::move(listener);
}

bool SharedItems::remove(int id) {
    std::lock_guard lock(mutex_);
    for (auto it = items_.begin(); it != items_.end(); ++it)
        if (it->id == id) {
            items_.erase(it);
            if (listener_) listener_(items_);
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
