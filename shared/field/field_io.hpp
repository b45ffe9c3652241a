// The field file, format "umf-field/1": JSON, one field per file.
#pragma once

#include <stdexcept>
#include <string>

#include "shared/field/field.hpp"

namespace umf {

inline constexpr const char* kFieldFormat = "umf-field/1";
// Far above any real field file (a 4096 x 4096 field is 17 MB of digits).
inline constexpr std::size_t kMaxFieldFileBytes = 32u << 20;

// A field file that cannot be read or does not describe a valid field. The
// message names the file (when there is one) and what is wrong.
class FieldFileError : public std::runtime_error {
public:
    using std::runtime_error::runtime_error;
};

Field parse_field(const std::string& json_text, const std::string& source_name = "field");
Field load_field(const std::string& path);

std::string field_to_json(const Field& field);
// Writes through a temporary file and a rename, so an existing file is never
// left half-written.
void save_field(const Field& field, const std::string& path);

}  // namespace umf
