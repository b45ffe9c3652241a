// Raises the edge contrast of a 4-orientable k-ary field without losing
// orientability: single module changes that make no window conflict and do
// not lower the contrast score.
#pragma once

#include <cstdint>

#include "shared/field/field.hpp"
#include "shared/field/window_classes.hpp"

namespace umf {

// Returns the number of changes made. The field must be 4-orientable.
long polish_contrast(Field& field, const WindowClasses& classes, long steps, std::uint64_t seed);

}  // namespace umf
