#include "requester/screen_lines.hpp"

#include <nlohmann/json.hpp>

namespace umf::requester {

namespace {

using Json = nlohmann::ordered_json;

// A name is anyone's to choose on the network: no control character may
// break the one-line-per-screen promise or move the terminal's cursor.
std::string printable(std::string text) {
    for (char& c : text)
        if (static_cast<unsigned char>(c) < 0x20 || c == 0x7f) c = '?';
    return text;
}

}  // namespace

std::string screen_line(const native::AnnouncedScreen& s) {
    std::string addresses;
    for (const auto& a : s.addresses) addresses += (addresses.empty() ? "" : ",") + a;
    std::string line = printable(s.name) + "  https://" + printable(s.host) + ":" + std::to_string(s.port) + "  " +
                       printable(addresses.empty() ? "-" : addresses) + "  " +
                       (s.fingerprint.empty() ? "no fingerprint" : "fp " + s.fingerprint);
    if (s.paired) line += "  (paired)";
    return line;
}

std::string screen_json(const native::AnnouncedScreen& s, bool with_paired) {
    Json j;
    j["name"] = s.name;
    j["host"] = s.host;
    j["port"] = s.port;
    j["addresses"] = s.addresses;
    if (!s.fingerprint.empty()) j["fingerprint"] = s.fingerprint;
    if (!s.version.empty()) j["version"] = s.version;
    if (with_paired) j["paired"] = s.paired;
    // Names come from the network, and nlohmann throws on bytes that are not
    // UTF-8 unless told to replace them.
    return j.dump(-1, ' ', false, Json::error_handler_t::replace);
}

}  // namespace umf::requester
