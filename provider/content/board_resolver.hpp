// Resolver 1: the items of the board the provider shows full screen.
#pragma once

#include <vector>

#include "provider/board/board.hpp"
#include "provider/content/resolver.hpp"

namespace umf::provider {

// A file or URL item as what a grab takes; shared by the board and by items
// shared on purpose.
Resolved resolved_item(const std::string& title, const std::optional<std::filesystem::path>& file,
                       const std::optional<std::string>& url);

class BoardResolver : public Resolver {
public:
    // `tiles` as layout_board gave them for `screen`.
    BoardResolver(Board board, std::vector<PixelRect> tiles, int screen = 0);
    const char* name() const override { return "board"; }
    std::optional<Resolved> resolve(const ScreenPoint& point, Purpose purpose) const override;

    const Board& board() const { return board_; }
    const std::vector<PixelRect>& tiles() const { return tiles_; }

private:
    Board board_;
    std::vector<PixelRect> tiles_;
    int screen_;
};

}  // namespace umf::provider
