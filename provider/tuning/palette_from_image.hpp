// A field palette taken from what the screen shows (thesis Ch. 8.1): a field
// drawn in the colours already on screen blends with them, where the field's
// own black and white would stand out.
#pragma once

#include <QImage>
#include <string>
#include <vector>

namespace umf::provider {

// Up to `colours` dominant colours of the image's opaque pixels as "#rrggbb",
// sorted dark to light by luma. k-means over a colour histogram, seeded
// farthest-first so the colours are distinct rather than shades of the one
// that covers the most pixels. Fewer when the image holds fewer distinct
// colours (none for an empty or fully transparent image); `colours` below 1
// gives none. Deterministic: the same image gives the same palette.
std::vector<std::string> palette_from_image(const QImage& image, int colours);

}  // namespace umf::provider
