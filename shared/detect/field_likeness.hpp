// Whether a grid read from the image is a marker field at all, whichever
// field: a field's modules are nearly all readable and take each value about
// as often as the others (the generator balances them), where content that
// happens to line up into a grid gives cells of its background mostly, or
// cells that do not read. A grid that reads as a field and yet as none of
// this field's places shows another screen's field.
#pragma once

#include "shared/detect/module_grid.hpp"
#include "shared/detect/placement_vote.hpp"

namespace umf {

struct FieldLikenessOptions {
    double min_known = 0.85;        // of the grid's modules, read
    double max_value_share = 0.75;  // of the read modules, taking any one value
    // Windows agreeing on one place of this field that chance gives a
    // grid of another field: about one window in seven of a 64 x 36 binary
    // field's 4 x 4 windows is also one of another's, at random places.
    int max_agreeing = 2;
};

// The windows read whole from `grid` when it reads as a field and this
// field's `vote` over it found no place; 0 otherwise.
int foreign_field_windows(const ModuleGrid& grid, const VoteResult& vote, const FieldLikenessOptions& options = {});

}  // namespace umf
