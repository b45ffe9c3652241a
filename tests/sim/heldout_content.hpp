// Screen contents for the held-out benchmark set only: desktops the detector
// was never tuned on, made apart from screen_content's (which the tuning set
// uses) so neither set's screens change with the other's. A spreadsheet (a
// grid of thin lines and numbers), a dark-mode editor with a file tree and a
// minimap, a frame of a film in a player (soft shapes, letterbox bars), a
// landscape photo (sky, hills, foliage texture) and a board of tiles (cards
// in columns). Contents depend only on kind, size and seed.
#pragma once

#include <opencv2/core.hpp>

#include <array>
#include <cstdint>

namespace umf::sim {

enum class HeldoutContent { spreadsheet, dark_editor, video_frame, landscape, board_tiles };

inline constexpr std::array<HeldoutContent, 5> kAllHeldoutContents = {
    HeldoutContent::spreadsheet, HeldoutContent::dark_editor, HeldoutContent::video_frame, HeldoutContent::landscape,
    HeldoutContent::board_tiles};

const char* to_string(HeldoutContent content);

// A BGR 8-bit image of the given size; sizes of text and cells scale with
// the height (laid out for 1440 lines).
cv::Mat make_heldout_screen(HeldoutContent content, cv::Size size, std::uint64_t seed);

}  // namespace umf::sim
