// Single-use upload links for accepted file puts (docs/PROTOCOL.md, "Upload"),
// as DownloadTable is for grabs: 128 random bits are the capability, the
// first PUT takes the entry out, an entry not taken within its lifetime is
// gone, and the table holds a bounded number of entries.
#pragma once

#include <chrono>
#include <cstdint>
#include <filesystem>
#include <map>
#include <mutex>
#include <optional>
#include <string>
#include <string_view>

#include "protocol/messages.hpp"

namespace umf::provider {

inline constexpr const char* kUploadPrefix = "/up/";

struct UploadEntry {
    std::uint64_t session = 0;  // SessionState::id of the session that put it
    protocol::RequestId id;     // the put's
    std::uint64_t offer = 0;    // PutOffer::id
    std::string name;           // safe file name the put asked for
    std::string mime;
    std::int64_t size = 0;
    std::string sha256;          // 64 lowercase hex digits
    bool open = false;           // open with the desktop's application once saved
    std::filesystem::path folder;
};

class UploadTable {
public:
    using Clock = std::chrono::steady_clock;

    explicit UploadTable(std::chrono::milliseconds ttl = std::chrono::seconds(60), std::size_t max_entries = 256);

    // The link path ("/up/<22 base64url characters>"); the oldest entry makes
    // room when the table is full.
    std::string add(UploadEntry entry, Clock::time_point now = Clock::now());
    // The entry of a request target ("/up/..."; a query is ignored), taken
    // out; nullopt when unknown, used or expired.
    std::optional<UploadEntry> take(std::string_view target, Clock::time_point now = Clock::now());
    std::size_t size() const;

private:
    struct Slot {
        UploadEntry entry;
        Clock::time_point expires;
    };
    std::chrono::milliseconds ttl_;
    std::size_t max_entries_;
    mutable std::mutex mutex_;
    std::map<std::string, Slot, std::less<>> slots_;
};

}  // namespace umf::provider
