#include "requester/device_name.hpp"

#include <unistd.h>

#include <array>
#include <fstream>
#include <random>
#include <system_error>

#include "requester/download_dir.hpp"
#include "requester/pinned_tls.hpp"
#include "shared/io/atomic_file.hpp"
#include "shared/protocol/messages.hpp"

namespace umf::requester {

namespace {

constexpr const char* kPrefix = "umf-requester-";

bool well_formed(const std::string& name) {
    if (name.size() <= std::char_traits<char>::length(kPrefix) || name.size() > protocol::kMaxDeviceBytes) return false;
    for (char c : name)
        if (c < 0x21 || c > 0x7e) return false;
    return true;
}

std::string fresh_name() {
    std::random_device random;
    std::string name = kPrefix;
    for (int i = 0; i < 4; ++i) {
        const std::uint32_t x = random();
        for (int b = 0; b < 8; ++b) name += "0123456789abcdef"[(x >> (4 * b)) & 15];
    }
    return name;
}

}  // namespace

std::string client_name() {
    std::string name = user_agent();
    std::array<char, 256> host{};
    if (::gethostname(host.data(), host.size() - 1) != 0 || host[0] == '\0') return name;
    std::string clean;
    for (const char* c = host.data(); *c && clean.size() < 64; ++c) clean += (*c > 0x20 && *c < 0x7f) ? *c : '_';
    return name + " on " + clean;
}

std::filesystem::path default_device_file() { return config_home() / "umf" / "requester-device"; }

std::string device_name(const std::filesystem::path& file, std::string& note) {
    {
        std::ifstream in(file);
        std::string kept;
        if (in && std::getline(in, kept) && well_formed(kept)) return kept;
    }
    std::string name = fresh_name();
    try {
        std::error_code ec;
        std::filesystem::create_directories(file.parent_path(), ec);
        write_file_atomically(file.string(), name + "\n");
    } catch (const std::exception& e) {
        note = std::string("this device's name cannot be kept (") + e.what() +
               "): screens will ask again next time";
    }
    return name;
}

}  // namespace umf::requester
