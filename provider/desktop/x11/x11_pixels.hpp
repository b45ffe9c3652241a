// An X server's image as the desktop seam's Capture (0xffRRGGBB a pixel),
// whatever the visual's masks and byte order: the common 32-bit layout is
// copied a row at a time, anything else read pixel by pixel.
#pragma once

#include "provider/desktop/desktop.hpp"

// Xlib's types, declared rather than included: Xlib's macros (None, Status,
// Bool) stay out of every file that includes this one.
struct _XImage;

namespace umf::provider {

// `visual_class` is the visual's (TrueColor, ...), or -1 when unknown.
// Throws std::runtime_error for a screen without true colour.
Capture capture_from_ximage(_XImage& image, int visual_class);

}  // namespace umf::provider
