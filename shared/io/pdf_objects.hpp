// A PDF 1.4 file around its objects: the header (its second line's high
// bytes tell transfer tools the file is binary), the objects numbered from 1,
// and a cross-reference table with the exact byte offsets readers check.
// Object 1 must be the catalog. The field renderer, the provider's demo
// leaflet and the tests' documents all write their PDFs through it.
#pragma once

#include <string>
#include <vector>

namespace umf::io {

// `info_object`: the number of the document information dictionary among
// `objects` (1-based), or 0 for none.
std::string pdf_from_objects(const std::vector<std::string>& objects, int info_object = 0);

}  // namespace umf::io
