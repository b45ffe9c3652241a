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

#include "provider/content/resolver.hpp"
#include "shared/protocol/messages.hpp"

#include "provider/common/one_time_links.hpp"

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
    std::optional<ScreenPoint> at;  // where the phone pointed: the opened file's window goes there
};

class UploadTable : public OneTimeLinks<UploadEntry> {
public:
    explicit UploadTable(std::chrono::milliseconds ttl = std::chrono::seconds(60),
                           std::size_t max_entries = 256)
        : OneTimeLinks(kUploadPrefix, ttl, max_entries) {}
};

}  // namespace umf::provider
