// One-time download links (docs/PROTOCOL.md, "Downloads"). A grab that
// resolves a file or a snapshot registers it here and sends the link; the
// first GET of the link takes the entry out, so a link works once, and an
// entry not taken within its lifetime is gone too. The link is 128 random
// bits: it is the capability, nothing else on the desktop can be named.
#pragma once

#include <chrono>
#include <cstdint>
#include <filesystem>
#include <map>
#include <memory>
#include <mutex>
#include <optional>
#include <string>
#include <string_view>

namespace umf::provider {

inline constexpr const char* kDownloadPrefix = "/dl/";

struct DownloadEntry {
    std::string name;  // offered file name, already safe (protocol::safe_file_name)
    std::string mime;
    std::int64_t size = 0;
    std::string sha256;  // may be empty
    // Exactly one of these: a file the provider resolved, or bytes it made.
    std::optional<std::filesystem::path> file;
    std::shared_ptr<const std::string> bytes;
};

class DownloadTable {
public:
    using Clock = std::chrono::steady_clock;

    explicit DownloadTable(std::chrono::milliseconds ttl = std::chrono::seconds(60),
                           std::size_t max_entries = 4096);

    // The link path ("/dl/<22 base64url characters>"). When the table is
    // full the oldest entry makes room.
    std::string add(DownloadEntry entry, Clock::time_point now = Clock::now());
    // The entry for a request target ("/dl/..."; a query is ignored), taken
    // out; nullopt when unknown, used or expired.
    std::optional<DownloadEntry> take(std::string_view target, Clock::time_point now = Clock::now());
    std::size_t size() const;
    std::chrono::milliseconds ttl() const { return ttl_; }

private:
    struct Slot {
        DownloadEntry entry;
        Clock::time_point expires;
    };
    void drop_expired(Clock::time_point now);

    std::chrono::milliseconds ttl_;
    std::size_t max_entries_;
    mutable std::mutex mutex_;
    std::map<std::string, Slot, std::less<>> slots_;
};

}  // namespace umf::provider
