// Download links (docs/PROTOCOL.md, "Downloads"). A grab that resolves a file
// or a snapshot registers it here and sends the link. The link stays good
// while its download is unfinished, so a requester whose connection was cut
// asks again for the rest (HTTP Range); it is gone once a download of it
// has completed, or when nothing has used it for the table's lifetime (the
// lifetime counts from the grab, then from the end of the last transfer). The
// link is 128 random bits: it is the capability, nothing else on the desktop
// can be named. Thread-safe.
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

#include "provider/content/file_facts.hpp"
#include "native/hash_checkpoints.hpp"

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
    std::int64_t leased_ctime_ns = 0;  // FileFacts's
    std::shared_ptr<const std::string> bytes;
    // The pairing token of the session that grabbed it: a download presents
    // it ("Authorization: Bearer TOKEN"), so a link that leaked is of no use
    // without it. Empty: nothing asked (a provider in public mode).
    std::string token;
};

// What one transfer of a link holds: the entry, and the file's hash states
// that earlier transfers of it saved, so a resumed one checks the whole file
// without reading it all again.
struct DownloadCheckout {
    std::string key;
    std::shared_ptr<const DownloadEntry> entry;
    std::shared_ptr<native::HashCheckpoints> checkpoints;
};

class DownloadTable {
public:
    using Clock = std::chrono::steady_clock;

    explicit DownloadTable(std::chrono::milliseconds ttl = std::chrono::seconds(60), std::size_t max_entries = 4096)
        : ttl_(ttl), max_entries_(max_entries > 0 ? max_entries : 1) {}

    // The link path ("/dl/" + key). When the table is full, the idle entry
    // that expires first makes room.
    std::string add(DownloadEntry entry, Clock::time_point now = Clock::now());

    // A transfer of the link a request names (a query is ignored) begins:
    // nullopt when the link is unknown, completed or expired. The entry
    // does not expire while a transfer of it runs.
    std::optional<DownloadCheckout> begin(std::string_view target, Clock::time_point now = Clock::now());
    // The transfer ended: a complete one ends the link, a broken one leaves
    // it for the table's lifetime from now, for the rest to be asked for.
    void end(const DownloadCheckout& checkout, bool complete, Clock::time_point now = Clock::now());

    std::size_t size() const;
    std::chrono::milliseconds ttl() const { return ttl_; }

private:
    struct Slot {
        std::shared_ptr<const DownloadEntry> entry;
        std::shared_ptr<native::HashCheckpoints> checkpoints;
        Clock::time_point expires;
        int transfers = 0;  // running now
    };

    void forget_expired(Clock::time_point now);

    std::chrono::milliseconds ttl_;
    std::size_t max_entries_;
    mutable std::mutex mutex_;
    std::map<std::string, Slot, std::less<>> slots_;
};

}  // namespace umf::provider
