// The field file (shared/field/field_io.hpp, "umf-field/1"), which umf-field
// and the provider read from disk and a requester receives inside a welcome:
// any text is either refused with FieldFileError or gives a valid field,
// and a field read is written out and read back.
#include <cstddef>
#include <cstdint>
#include <string>

#include "shared/field/field_io.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    const std::string text(reinterpret_cast<const char*>(data), size);
    umf::Field field;
    try {
        field = umf::parse_field(text, "fuzz");
    } catch (const umf::FieldFileError&) {
        return 0;
    }
    // parse_field promises a valid field, and field_to_json writes any valid one.
    (void)umf::parse_field(umf::field_to_json(field), "fuzz again");
    return 0;
}
