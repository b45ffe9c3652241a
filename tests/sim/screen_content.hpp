// Synthetic desktop screens for the camera simulator: what the faint field is
// mixed into. Each kind stresses the detector differently: black text on
// white (document), bright thin strokes on dark (code_dark), mixed pictures and
// text (web_page), texture everywhere (photo), nothing at all (blank), and a
// grid of its own lined up with the field's (spreadsheet: rules every cell).
// Contents depend only on kind, size and seed.
#pragma once

#include <opencv2/core.hpp>

#include <array>
#include <cstdint>

namespace umf::sim {

enum class ScreenKind { document, code_dark, web_page, photo, blank, spreadsheet };

// The screens the benchmark's categories take turns with, frame by frame.
inline constexpr std::array<ScreenKind, 5> kEverydayScreenKinds = {
    ScreenKind::document, ScreenKind::code_dark, ScreenKind::web_page, ScreenKind::photo, ScreenKind::blank};

// Every kind, in the enum's order.
inline constexpr std::array<ScreenKind, 6> kAllScreenKinds = {ScreenKind::document, ScreenKind::code_dark,
                                                              ScreenKind::web_page, ScreenKind::photo,
                                                              ScreenKind::blank,    ScreenKind::spreadsheet};

const char* to_string(ScreenKind kind);

// A BGR 8-bit image of the given size. Text sizes scale with the height, so a
// 3840 x 2160 screen looks like a 1920 x 1080 one at twice the resolution.
cv::Mat make_screen(ScreenKind kind, cv::Size size, std::uint64_t seed);

}  // namespace umf::sim
