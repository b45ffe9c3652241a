#include "requester/paired_screens.hpp"

#include <algorithm>
#include <fstream>
#include <iterator>
#include <nlohmann/json.hpp>
#include <system_error>

#include "native/private_file.hpp"
#include "requester/cli.hpp"
#include "requester/download_dir.hpp"
#include "shared/io/atomic_file.hpp"

namespace umf::requester {

namespace {

constexpr const char* kFormat = "umf-requester-screens/1";
constexpr std::uintmax_t kMaxFileBytes = 256 * 1024;
constexpr std::size_t kMaxNameBytes = 128;

InputError not_a_list(const std::filesystem::path& file, const std::string& why) {
    return InputError(file.string() + ": " + why + " (fix it, or remove it and pair again)");
}

}  // namespace

std::filesystem::path default_paired_screens_file() { return config_home() / "umf" / "requester-screens.json"; }

std::vector<PairedScreen> read_paired_screens(const std::filesystem::path& file) {
    std::error_code ec;
    if (!std::filesystem::exists(file, ec)) return {};
    const auto size = std::filesystem::file_size(file, ec);
    if (ec) throw InputError(file.string() + ": cannot read: " + ec.message());
    if (size > kMaxFileBytes) throw not_a_list(file, "larger than " + std::to_string(kMaxFileBytes) + " bytes");
    std::ifstream in(file, std::ios::binary);
    if (!in) throw InputError(file.string() + ": cannot read");
    const std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    const auto doc = nlohmann::json::parse(text, nullptr, false);
    if (!doc.is_object() || !doc.contains("format") || doc["format"] != kFormat || !doc.contains("screens") ||
        !doc["screens"].is_array())
        throw not_a_list(file, std::string("not a list of paired screens (\"format\": \"") + kFormat + "\")");
    std::vector<PairedScreen> screens;
    for (const auto& entry : doc["screens"]) {
        if (!entry.is_object() || !entry.contains("url") || !entry["url"].is_string() ||
            !entry.value("name", nlohmann::json()).is_string())
            throw not_a_list(file, "a screen is not {\"name\": ..., \"url\": ...}");
        PairedScreen s;
        s.name = entry["name"].get<std::string>().substr(0, kMaxNameBytes);
        s.url_text = entry["url"].get<std::string>();
        try {
            s.url = protocol::parse_pairing_url(s.url_text);
        } catch (const protocol::PairingUrlError& e) {
            throw not_a_list(file, "the pairing URL of " + s.name + ": " + e.what());
        }
        if (screens.size() < kMaxPairedScreens) screens.push_back(std::move(s));
    }
    return screens;
}

void write_paired_screens(const std::filesystem::path& file, const std::vector<PairedScreen>& screens) {
    nlohmann::ordered_json list = nlohmann::ordered_json::array();
    for (const auto& s : screens) list.push_back({{"name", s.name}, {"url", s.url_text}});
    const nlohmann::ordered_json doc{{"format", kFormat}, {"screens", std::move(list)}};
    std::error_code ec;
    std::filesystem::create_directories(file.parent_path(), ec);
    try {
        write_private_file(file, doc.dump(2, ' ', false, nlohmann::ordered_json::error_handler_t::replace) + "\n");
    } catch (const FileWriteError& e) {
        throw InputError(e.what());
    }
}

std::vector<PairedScreen> with_screen_first(std::vector<PairedScreen> screens, PairedScreen screen) {
    std::erase_if(screens, [&](const PairedScreen& s) { return s.url.fingerprint == screen.url.fingerprint; });
    screens.insert(screens.begin(), std::move(screen));
    if (screens.size() > kMaxPairedScreens) screens.resize(kMaxPairedScreens);
    return screens;
}

bool forget_screen(std::vector<PairedScreen>& screens, const std::string& name_or_url) {
    return std::erase_if(screens, [&](const PairedScreen& s) {
               return s.name == name_or_url || s.url_text == name_or_url;
           }) > 0;
}

}  // namespace umf::requester
