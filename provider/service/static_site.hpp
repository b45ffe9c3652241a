// The web client's files (web/), served over HTTPS. Read into memory once at
// start-up: a request's path is only ever a key into this map, never a path
// on the file system.
#pragma once

#include <filesystem>
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <string_view>

namespace umf::provider {

struct StaticFile {
    std::string mime;
    std::shared_ptr<const std::string> bytes;
    std::string download_name;  // set: sent as an attachment of that name
};

class StaticSite {
public:
    inline static constexpr std::size_t kMaxFiles = 4096;
    inline static constexpr std::size_t kMaxTotalBytes = 64u << 20;

    // A small built-in page saying how to pair, for a provider built without
    // the web client.
    StaticSite();
    // Every regular file under `root` (no hidden ones), as "/relative/path";
    // "/" serves "/index.html", the built-in page when the folder has none.
    // Types: text/javascript (.js, .mjs), application/wasm, text/css,
    // text/html, application/json, application/manifest+json
    // (.webmanifest), image/svg+xml, image/png, image/x-icon and the rest of
    // mime_for (content/file_facts.hpp); text and JSON in UTF-8. Throws
    // std::runtime_error when the folder cannot be read or exceeds the limits
    // above.
    static StaticSite from_folder(const std::filesystem::path& root);

    // Serves `file` at `path` ("/dir/name") besides the folder's files (the
    // screen's root for the phone page); replaces one of the same path.
    void add(const std::string& path, StaticFile file) { files_[path] = std::move(file); }

    // The file for a request target (a query or fragment is ignored).
    std::optional<StaticFile> find(std::string_view target) const;
    std::size_t size() const { return files_.size(); }

private:
    std::map<std::string, StaticFile, std::less<>> files_;
};

}  // namespace umf::provider
