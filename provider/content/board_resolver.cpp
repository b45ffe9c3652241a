#include "provider/content/board_resolver.hpp"

#include <stdexcept>

#include "provider/content/file_facts.hpp"

namespace umf::provider {

Resolved resolved_item(const std::string& title, const std::optional<std::filesystem::path>& file,
                       const std::optional<std::string>& url) {
    Resolved r;
    r.title = title;
    if (file) {
        r.kind = protocol::ContentKind::file;
        r.file = *file;
        r.name = protocol::safe_file_name(file->filename().string());
        r.mime = mime_for(*file);
    } else if (url) {
        r.kind = protocol::ContentKind::url;
        r.url = *url;
    }
    return r;
}

BoardResolver::BoardResolver(Board board, std::vector<PixelRect> tiles, int screen)
    : board_(std::move(board)), tiles_(std::move(tiles)), screen_(screen) {
    if (tiles_.size() != board_.items.size()) throw std::invalid_argument("a board needs one tile per item");
}

std::optional<Resolved> BoardResolver::resolve(const ScreenPoint& point, Purpose) const {
    if (point.screen != screen_) return std::nullopt;
    // Later items are drawn over earlier ones where explicit rectangles overlap.
    for (std::size_t i = tiles_.size(); i-- > 0;)
        if (tiles_[i].contains(point.x, point.y)) {
            const BoardItem& item = board_.items[i];
            return resolved_item(item.title, item.file, item.url);
        }
    return std::nullopt;
}

}  // namespace umf::provider
