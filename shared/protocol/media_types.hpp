// The media type a file name suggests, for the `mime` of content and puts:
// both the provider (describing its files) and the requesters (announcing a
// file they put) name types from the same small table.
#pragma once

#include <string>
#include <string_view>

namespace umf::protocol {

// "application/pdf" for "x.PDF" (the extension after the last dot, in any
// case); application/octet-stream when the extension is not in the table.
std::string media_type_for(std::string_view file_name);

}  // namespace umf::protocol
