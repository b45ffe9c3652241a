// A board: the provider's own full-screen window of tiles, each a file or a
// URL: kiosks, posters, lecture screens, and the built-in demo. A board file
// is JSON:
//
//   {"format": "umf-board/1", "title": "Open day", "columns": 3,
//    "items": [
//      {"title": "Timetable", "file": "timetable.pdf", "thumbnail": "timetable.png"},
//      {"title": "Project site", "url": "https://example.org/"},
//      {"title": "Map", "file": "map.png", "rect": [1200, 600, 600, 400]}]}
//
// "file" and "thumbnail" are relative to the board file's folder (or
// absolute); each item has exactly one of "file" and "url". Items with a
// "rect" (x, y, width, height in screen pixels) are placed there; the others
// are laid out in a grid of "columns" (0 or absent: chosen to suit the
// screen) below the title.
#pragma once

#include <filesystem>
#include <optional>
#include <stdexcept>
#include <string>
#include <string_view>
#include <vector>

namespace umf::provider {

struct PixelRect {
    int x = 0, y = 0, width = 0, height = 0;
    bool contains(double px, double py) const { return px >= x && px < x + width && py >= y && py < y + height; }
    bool operator==(const PixelRect&) const = default;
};

struct BoardItem {
    std::string title;                           // not empty
    std::optional<std::filesystem::path> file;   // absolute once loaded
    std::optional<std::string> url;              // http: or https:
    std::optional<std::filesystem::path> thumbnail;
    std::optional<PixelRect> rect;
    bool operator==(const BoardItem&) const = default;
};

struct Board {
    std::string title;
    int columns = 0;  // 0: automatic
    std::vector<BoardItem> items;  // 1..kMaxBoardItems
    bool operator==(const Board&) const = default;
};

inline constexpr std::size_t kMaxBoardItems = 256;
inline constexpr std::size_t kMaxBoardFileBytes = 1u << 20;
inline constexpr const char* kBoardFormat = "umf-board/1";
inline constexpr int kMaxBoardColumns = 64;
inline constexpr std::size_t kMaxBoardTitleBytes = 512;
inline constexpr std::size_t kMaxBoardUrlBytes = 8192;
inline constexpr std::size_t kMaxBoardPathBytes = 4096;
// Rect members beyond this are refused: no screen is that large, and it keeps
// x + width within int.
inline constexpr int kMaxBoardRectCoordinate = 1 << 20;

class BoardError : public std::runtime_error {
public:
    using std::runtime_error::runtime_error;
};

// Parses a board; relative paths are taken from base_dir. Throws BoardError
// naming the item and member at fault (an unknown member too, since a
// misspelt one would otherwise be silently ignored). Files need not exist
// yet: a missing file is the resolver's business at grab time.
Board parse_board(std::string_view json, const std::filesystem::path& base_dir);
// Reads and parses a board file; BoardError on anything wrong, naming the file.
Board load_board(const std::filesystem::path& file);

// Each item's tile on a screen of the given size, in item order: the item's
// rect when it has one, otherwise its cell of the grid. Tiles do not overlap
// the title bar and lie within the screen.
std::vector<PixelRect> layout_board(const Board& board, int screen_width, int screen_height);

// The height of the title bar across the top of the screen (0 when the board
// has no title): about 8 % of the screen, at least 48 pixels, at most a
// quarter of the screen. layout_board keeps the tiles below it and the board
// window paints the title in it.
int board_title_height(const Board& board, int screen_height);

// The board as a "umf-board/1" file: paths inside base_dir are written
// relative to it, others absolute. parse_board(board_to_json(b, d), d) == b.
std::string board_to_json(const Board& board, const std::filesystem::path& base_dir);

// The built-in demo board: writes its six items' files (a text note, a PNG
// picture, a PDF, a CSV table; the rest are URLs) into `dir` (created when
// missing) and returns the board pointing at them. Also writes the board
// itself as "board.json" in `dir`, for `umf-provider compose --board`. Same
// bytes every time, each file replaced atomically. Throws std::runtime_error
// (FileWriteError) naming the file that cannot be written.
Board write_demo_board(const std::filesystem::path& dir);

}  // namespace umf::provider
