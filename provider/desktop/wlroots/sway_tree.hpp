// Sway's GET_TREE and GET_OUTPUTS read as the seam's windows and outputs.
// Pure functions over the JSON, so every layout is tested from a sample.
#pragma once

#include <nlohmann/json.hpp>
#include <optional>
#include <vector>

#include "provider/desktop/desktop.hpp"

namespace umf::provider {

// The windows shown, top-most first: on each output's visible workspace the
// fullscreen window, then the floating ones (the last drawn first), then the
// tiled ones; a global fullscreen window before everything. Views hidden in
// a tabbed or stacked container are left out. rect is the frame: the
// content `rect` with the title bar (`deco_rect`) above it.
std::vector<WindowInfo> sway_visible_windows(const nlohmann::json& tree);

// The ids of every view in the tree, shown or not (scratchpad included).
std::vector<unsigned long> sway_window_ids(const nlohmann::json& tree);

// The view with con id `id`, wherever it is.
std::optional<WindowInfo> sway_window(const nlohmann::json& tree, unsigned long id);

// The view that has the focus.
std::optional<unsigned long> sway_focused_window(const nlohmann::json& tree);

// The active outputs of GET_OUTPUTS.
std::vector<DesktopOutput> sway_outputs(const nlohmann::json& outputs);

// The first of `top_first` containing the point that the filter keeps.
std::optional<WindowInfo> topmost_window_at(const std::vector<WindowInfo>& top_first, double x, double y,
                                            const WindowFilter& filter);

}  // namespace umf::provider
