// Proves a field 4-orientable, or lists every conflict.
#pragma once

#include <string>
#include <vector>

#include "shared/field/field.hpp"

namespace umf {

struct WindowConflict {
    enum class Kind {
        duplicate,  // window a equals window b
        rotated,    // window a equals window b turned clockwise by quarter_turns * 90 degrees
        self,       // window a equals itself turned by quarter_turns * 90 degrees
    };
    Kind kind = Kind::duplicate;
    int row_a = 0, col_a = 0;  // top-left module of window a
    int row_b = 0, col_b = 0;  // top-left module of window b (== a for self)
    int quarter_turns = 0;
};

struct VerifyReport {
    long windows = 0;
    std::vector<WindowConflict> conflicts;
    bool orientable() const { return conflicts.empty(); }
};

// Every window of the field against every other window and against its own
// rotations, compared by the field's key. Works from module values directly,
// independent of the generator's bookkeeping.
VerifyReport verify_field(const Field& field);

// "window (3,7) equals window (10,2) turned 90 degrees"
std::string describe(const WindowConflict& conflict);

}  // namespace umf
