#include "shared/protocol/media_types.hpp"

#include <algorithm>
#include <cctype>

namespace umf::protocol {

namespace {

struct MediaType {
    const char* extension;
    const char* type;
};
constexpr MediaType kMediaTypes[] = {
    {".pdf", "application/pdf"},   {".png", "image/png"},       {".jpg", "image/jpeg"},
    {".jpeg", "image/jpeg"},       {".gif", "image/gif"},       {".webp", "image/webp"},
    {".svg", "image/svg+xml"},     {".txt", "text/plain"},      {".md", "text/markdown"},
    {".csv", "text/csv"},          {".html", "text/html"},      {".htm", "text/html"},
    {".json", "application/json"}, {".zip", "application/zip"}, {".mp4", "video/mp4"},
    {".webm", "video/webm"},       {".mp3", "audio/mpeg"},      {".odt", "application/vnd.oasis.opendocument.text"},
    {".ods", "application/vnd.oasis.opendocument.spreadsheet"},
    {".odp", "application/vnd.oasis.opendocument.presentation"},
    {".docx", "application/vnd.openxmlformats-officedocument.wordprocessingml.document"},
    {".xlsx", "application/vnd.openxmlformats-officedocument.spreadsheetml.sheet"},
    {".pptx", "application/vnd.openxmlformats-officedocument.presentationml.presentation"},
};

}  // namespace

std::string media_type_for(std::string_view file_name) {
    // The name's last component only: "a.d/README" has no extension.
    const auto slash = file_name.find_last_of("/\\");
    if (slash != std::string_view::npos) file_name.remove_prefix(slash + 1);
    const auto dot = file_name.rfind('.');
    if (dot == std::string_view::npos || dot == 0) return "application/octet-stream";
    std::string ext(file_name.substr(dot));
    std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return std::tolower(c); });
    for (const auto& m : kMediaTypes)
        if (ext == m.extension) return m.type;
    return "application/octet-stream";
}

}  // namespace umf::protocol
