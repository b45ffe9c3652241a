// A field the project ships (shared/data/fields), by its file name: what the
// tests of the detector, the overlay and the protocol read their field from.
#pragma once

#include <string>

#include "shared/field/field_io.hpp"

namespace umf::test {

inline Field shipped_field(const std::string& name) {
    return load_field(std::string(UMF_DATA_DIR) + "/fields/" + name);
}

}  // namespace umf::test
