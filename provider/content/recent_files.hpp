// The desktop's list of recently used files (the freedesktop XBEL file GTK,
// GLib and many other programs write), to find the document a window shows
// when its process does not name it: many viewers run as one process for
// all their windows, or are started over D-Bus without arguments.
#pragma once

#include <chrono>
#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <memory>
#include <mutex>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace umf::provider {

struct RecentFile {
    std::filesystem::path path;
    // The latest of the bookmark's added, modified and visited times and its
    // applications' times: when the file was last used.
    std::chrono::system_clock::time_point modified;
    std::string title;  // the bookmark's <title>, often empty
    std::string mime;   // the bookmark's mime type, often set
};

// Bigger files are not read: a sane list holds a few thousand entries.
inline constexpr std::size_t kMaxRecentFilesBytes = 16 * 1024 * 1024;

// $XDG_DATA_HOME/recently-used.xbel, or ~/.local/share/recently-used.xbel;
// empty when neither variable helps.
std::filesystem::path default_recent_files_path();

// The local file a file: URL names (host empty or "localhost"), percent-
// decoded; nullopt for other URLs, relative paths or a NUL in the path.
std::optional<std::filesystem::path> file_url_to_path(std::string_view url);

// ISO 8601 as GLib writes it ("2024-03-01T09:30:00.123456Z", or with a
// "+01:00" offset); nullopt when it is not that.
std::optional<std::chrono::system_clock::time_point> parse_iso8601(std::string_view text);

// The local files of an XBEL document, in document order. Malformed XML or a
// document that is not XBEL gives an empty list; never throws on content.
std::vector<RecentFile> parse_recent_files(std::string_view xbel);

// parse_recent_files of the file; empty when it is missing, unreadable or
// larger than max_bytes.
std::vector<RecentFile> read_recent_files(const std::filesystem::path& file,
                                          std::size_t max_bytes = kMaxRecentFilesBytes);

// Whether `name` occurs in `title` as a whole: not as part of a longer name
// ("a.pdf" is not in "data.pdf - mupdf", "report.pdf" is in "report.pdf —
// Document Viewer" and in "[report.pdf]").
bool title_mentions(std::string_view title, std::string_view name);

// The file a window titled `window_title` most likely shows: among existing
// regular files whose base name the title mentions, the most recently used.
// Failing that, the same by the bookmark's title, then by the base name
// without its extension (viewers that drop it: "report — Document Viewer").
std::optional<std::filesystem::path> match_by_title(const std::vector<RecentFile>& entries,
                                                    std::string_view window_title);

// The list of one file, read again only when the file's size or time
// changes, since aims ask several times a second. Thread-safe.
class RecentFilesCache {
public:
    explicit RecentFilesCache(std::filesystem::path file);
    std::shared_ptr<const std::vector<RecentFile>> entries() const;
    const std::filesystem::path& file() const { return file_; }

private:
    std::filesystem::path file_;
    mutable std::mutex mutex_;
    mutable std::shared_ptr<const std::vector<RecentFile>> entries_;
    mutable std::filesystem::file_time_type stamp_{};
    mutable std::uintmax_t size_ = 0;
};

}  // namespace umf::provider
