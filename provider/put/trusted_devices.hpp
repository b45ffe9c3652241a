// The devices whose puts land without asking: the person at the screen said
// "always from this device". A device is the name a requester sends in its
// hello (`device`, docs/PROTOCOL.md). Kept in a small JSON file in the
// provider's config dir, rewritten whole and atomically on each change
// (shared/io/atomic_file), so a crash leaves the old list or the new.
// Each device keeps what its files do: saved, or saved and opened, as the
// answer given together with "always" (URLs are always opened). The file
// lists the devices in "devices" and those whose files open also in
// "open_files", so a list written before that choice existed reads as
// "save", and an older provider reading a newer list still trusts them all.
#pragma once

#include <cstddef>
#include <filesystem>
#include <mutex>
#include <optional>
#include <set>
#include <string>
#include <string_view>
#include <vector>

#include "provider/put/put_decision.hpp"

namespace umf::provider {

inline constexpr const char* kTrustedDevicesFile = "trusted-devices.json";
inline constexpr std::size_t kMaxTrustedDevices = 1024;

class TrustedDevices {
public:
    // Reads `file` when it exists; one that cannot be read or parsed counts
    // as empty (and is replaced at the next add). Empty path: memory only.
    explicit TrustedDevices(std::filesystem::path file = {});

    bool contains(std::string_view device) const;
    // What a trusted device's files do (save or open); nullopt when the
    // device is not trusted.
    std::optional<PutAnswer> files_answer(std::string_view device) const;
    // Remembers a device and saves the list; false when it cannot be saved
    // (it is still trusted while the provider runs). Beyond kMaxTrustedDevices
    // the oldest names are forgotten. `files`: save or open for its files
    // from now on; nullopt (a URL's "always") keeps a known device's choice,
    // save for a new one.
    bool add(const std::string& device, std::optional<PutAnswer> files = std::nullopt);
    bool remove(const std::string& device);
    std::size_t size() const;

private:
    bool save_locked() const;

    std::filesystem::path file_;
    mutable std::mutex mutex_;
    std::set<std::string, std::less<>> devices_;
    std::vector<std::string> order_;  // oldest first
    std::set<std::string, std::less<>> open_files_;  // the trusted devices whose files are opened
};

}  // namespace umf::provider
