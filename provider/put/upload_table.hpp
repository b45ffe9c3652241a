// Upload links for accepted file puts (docs/PROTOCOL.md, "Upload"), as
// DownloadTable is for grabs: 128 random bits are the capability. A link
// lasts until an upload through it is stored or fails for good; one that
// breaks off keeps its sink (the bytes so far) for the table's lifetime from
// its end, so the requester asks how much arrived (HEAD) and sends the rest
// (PUT with Upload-Offset). A link nobody used expires after the same time.
// The table holds a bounded number of links. Thread-safe.
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
#include <vector>

#include "provider/content/resolver.hpp"
#include "provider/put/upload_sink.hpp"
#include "shared/protocol/messages.hpp"

namespace umf::provider {

inline constexpr const char* kUploadPrefix = "/up/";

struct UploadEntry {
    std::uint64_t session = 0;  // SessionState::id of the session that put it
    protocol::RequestId id;     // the put's
    std::uint64_t offer = 0;    // PutOffer::id
    std::string name;           // safe file name the put asked for
    std::string mime;
    std::int64_t size = 0;
    std::string sha256;          // 64 lowercase hex digits; empty: named after the bytes (Upload-SHA256)
    bool open = false;           // open with the desktop's application once saved
    std::filesystem::path folder;
    std::optional<ScreenPoint> at;  // where the phone pointed: the opened file's window goes there
};

// One request's hold on a link: the put, and the sink once a request made it.
struct UploadCheckout {
    std::string key;
    UploadEntry entry;
    std::shared_ptr<UploadSink> sink;
};

// How a request through a link ended.
enum class UploadEnd {
    stored,  // the file is in place: the link ends
    failed,  // refused for good (no room, another hash, a wrong size): the link ends
    broken,  // the connection broke: the link waits for the rest
};

// A broken upload nobody went on with in time: its session is told.
struct AbandonedUpload {
    UploadEntry entry;
    std::int64_t received = 0;
};

class UploadTable {
public:
    using Clock = std::chrono::steady_clock;

    explicit UploadTable(std::chrono::milliseconds ttl = std::chrono::seconds(60), std::size_t max_entries = 256)
        : ttl_(ttl), max_entries_(max_entries > 0 ? max_entries : 1) {}

    // The link path ("/up/" + key). When the table is full, the idle link
    // that expires first makes room.
    std::string add(UploadEntry entry, Clock::time_point now = Clock::now());

    // A request through the link begins (a query is ignored): nullopt when
    // it is unknown, ended or expired. The link does not expire while a
    // request runs.
    std::optional<UploadCheckout> begin(std::string_view target, Clock::time_point now = Clock::now());
    // The sink the first request made, kept with the link; the one kept
    // already when another request made one first.
    std::shared_ptr<UploadSink> keep_sink(const UploadCheckout& checkout, std::shared_ptr<UploadSink> sink);
    void end(const UploadCheckout& checkout, UploadEnd how, Clock::time_point now = Clock::now());

    // Broken uploads whose time ran out, taken out of the table.
    std::vector<AbandonedUpload> take_abandoned(Clock::time_point now = Clock::now());
    // When the next broken upload runs out of time, if one waits.
    std::optional<Clock::time_point> next_abandon() const;

    std::size_t size() const;
    std::chrono::milliseconds ttl() const { return ttl_; }

private:
    struct Slot {
        UploadEntry entry;
        std::shared_ptr<UploadSink> sink;
        Clock::time_point expires;
        int requests = 0;  // running now
    };
    using Slots = std::map<std::string, Slot, std::less<>>;

    Slots::iterator find(std::string_view target, Clock::time_point now);

    std::chrono::milliseconds ttl_;
    std::size_t max_entries_;
    mutable std::mutex mutex_;
    Slots slots_;
};

}  // namespace umf::provider
