// A snapshot of part of one output through wlr-screencopy: a connection of
// its own per call, so any server thread may ask.
#pragma once

#include <chrono>
#include <cstdint>
#include <string>

#include "provider/desktop/desktop.hpp"

namespace umf::provider {

// The pixels of a shm frame as Capture's 0xffRRGGBB, rows flipped when the
// compositor says y_invert. Handles WL_SHM_FORMAT_XRGB8888 and ARGB8888
// (the same bytes on a little-endian machine, alpha dropped) and
// XBGR8888/ABGR8888; throws DesktopError for another format.
Capture capture_from_shm(const std::uint8_t* data, int width, int height, int stride, std::uint32_t format,
                         bool y_invert);

// `region` in the output's own logical coordinates. The answer has the
// region's size (a scaled output's physical pixels are scaled down to it).
// Throws DesktopError when the compositor refuses, offers no screencopy or
// does not answer within `timeout`.
Capture screencopy_region(const std::string& wayland_display, const std::string& output_name, const WindowRect& region,
                          std::chrono::milliseconds timeout = std::chrono::milliseconds(3000));

}  // namespace umf::provider
