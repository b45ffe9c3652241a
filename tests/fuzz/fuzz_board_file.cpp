// The board file (provider/board/board.hpp, "umf-board/1") that kiosks and
// posters are made of: any text is either refused with BoardError or gives a
// board that lays out on any screen and that board_to_json writes so that it
// reads back the same (its documented promise).
#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <string_view>

#include "provider/board/board.hpp"

namespace provider = umf::provider;

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    const std::string_view text(reinterpret_cast<const char*>(data), size);
    // Paths are only joined and normalised, never opened, so any folder will do.
    const std::filesystem::path base = "/fuzz/boards/open-day";
    provider::Board board;
    try {
        board = provider::parse_board(text, base);
    } catch (const provider::BoardError&) {
        return 0;
    }
    // The screens a board meets: the usual, a portrait one, a tiny one, a huge one.
    static constexpr int kScreens[][2] = {{1920, 1080}, {1080, 1920}, {1, 1}, {33, 7}, {65536, 65536}};
    for (const auto& screen : kScreens) {
        (void)provider::layout_board(board, screen[0], screen[1]);
        (void)provider::board_title_height(board, screen[1]);
    }
    if (provider::parse_board(provider::board_to_json(board, base), base) != board) __builtin_trap();
    return 0;
}
