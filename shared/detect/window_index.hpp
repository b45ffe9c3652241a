// Every window of a field under each of its four rotations, so one window
// read from the image gives a position in the field and the image's turn.
#pragma once

#include <cstdint>
#include <optional>
#include <unordered_map>
#include <vector>

#include "shared/field/field.hpp"
#include "shared/field/window_code.hpp"

namespace umf {

struct WindowMatch {
    int row = 0;  // top-left module of the field window
    int col = 0;
    // The observed window equals the field window turned clockwise by
    // quarter_turns * 90 degrees.
    int quarter_turns = 0;
};

class WindowIndex {
public:
    // Throws std::invalid_argument when the field is invalid or not
    // 4-orientable: a window that could stand in two places must never be
    // looked up.
    explicit WindowIndex(const Field& field);

    std::optional<WindowMatch> find(std::uint64_t code) const;
    const WindowCodec& codec() const { return codec_; }
    const Field& field() const { return field_; }

private:
    Field field_;
    WindowCodec codec_;
    // Small code spaces: a table of (window index * 4 + turn) + 1, 0 for none.
    std::vector<std::uint32_t> table_;
    std::unordered_map<std::uint64_t, std::uint32_t> map_;
};

}  // namespace umf
