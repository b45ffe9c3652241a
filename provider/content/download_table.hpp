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

#include "provider/common/one_time_links.hpp"
#include "provider/content/file_facts.hpp"

namespace umf::provider {

inline constexpr const char* kDownloadPrefix = "/dl/";

struct DownloadEntry {
    std::string name;  // offered file name, already safe (protocol::safe_file_name)
    std::string mime;
    std::int64_t size = 0;
    std::string sha256;
    // Exactly one of these: a file the provider resolved (as it was when
    // hashed: the download sends it only while it is still that file), or
    // bytes it made.
    std::optional<std::filesystem::path> file;
    FileIdentity identity;
    std::shared_ptr<const std::string> bytes;
};

class DownloadTable : public OneTimeLinks<DownloadEntry> {
public:
    explicit DownloadTable(std::chrono::milliseconds ttl = std::chrono::seconds(60),
                           std::size_t max_entries = 4096)
        : OneTimeLinks(kDownloadPrefix, ttl, max_entries) {}
};

}  // namespace umf::provider
