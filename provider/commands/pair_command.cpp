#include "provider/commands/pair_command.hpp"

#include <algorithm>
#include <filesystem>
#include <iostream>
#include <sstream>
#include <string>
#include <vector>
#include <nlohmann/json.hpp>

#include "provider/commands/common_options.hpp"
#include "provider/commands/control_client.hpp"
#include "provider/put/put_text.hpp"
#include "provider/screen/field_source.hpp"
#include "provider/service/control_socket.hpp"
#include "provider/service/pairing.hpp"
#include "provider/service/pairing_qr.hpp"
#include "provider/trust/tls_identity_store.hpp"

namespace umf::provider {

using cli::get;
using cli::has_flag;
using cli::UsageError;

namespace {

// The provider on `port` takes the new token at once (and with `field` the
// new field: its requesters get it as after a change of screens), when it
// runs on `dir`; one of another configuration keeps its own.
void tell_running_provider(unsigned short port, const std::filesystem::path& dir, bool field) {
    std::ostringstream why;
    const ControlAnswer answer = ask_running_provider(port, nlohmann::json{{"cmd", "rotated"}}, why);
    if (answer.exit != kOk) {
        std::cerr << why.str() << "umf-provider: the provider on port " << port
                  << " takes the new pairing from its next start; until then it takes the old one\n";
        return;
    }
    const std::filesystem::path its_dir = answer.json.value("config_dir", "");
    std::error_code ec;
    if (!std::filesystem::equivalent(its_dir, dir, ec)) {
        std::cerr << "umf-provider: the provider on port " << port << " has another configuration (" << its_dir.string()
                  << "), which stays as it was\n";
        return;
    }
    std::cerr << "umf-provider: the provider on port " << port << " takes only the new pairing now\n";
    if (!field) return;
    const std::string id = answer.json.value("field", "");
    if (answer.json.value("field_changed", false))
        std::cerr << "umf-provider: it shows the new field now (" << id
                  << "); its phones and webcams connect again and get it\n";
    else
        std::cerr << "umf-provider: it shows the shipped field (--shipped-field), which stays\n";
}

}  // namespace

int run_pair(const cli::Args& a) {
    // The running provider's port when one runs; the URL is for a port.
    const std::optional<unsigned short> running = running_provider_port(a);
    const unsigned short port = running.value_or(kDefaultPort);
    if (!running)
        std::cerr << "umf-provider: no provider is running; this URL is for port " << port
                  << ", the default (give --port P for a provider on another)\n";
    const std::string host = url_host(a, "0.0.0.0");
    const auto dir = config_dir_option(a);
    if (has_flag(a, "root") && !has_flag(a, "rotate")) throw UsageError("--root goes with --rotate");
    if (has_flag(a, "field") && !has_flag(a, "rotate")) throw UsageError("--field goes with --rotate");
    try {
        if (has_flag(a, "root")) {
            remove_root(dir);
            std::cerr << "umf-provider: a new screen root is made; every phone and webcam must pair again, and "
                         "phones that trusted the old root should remove it"
                      << (running ? " (the running provider serves the old one until it restarts)" : "") << "\n";
        }
        if (has_flag(a, "field")) {
            const FieldSource fields = rotate_field_seed(dir);
            std::cerr << "umf-provider: the screen's own field has a new seed (" << std::hex << fields.seed() << std::dec
                      << "); printed or composed pictures of the old field no longer point at this screen\n";
        }
        const TlsIdentity identity = load_or_create_tls_identity(dir);
        const std::string token = load_or_create_token(dir, has_flag(a, "rotate"));
        if (running && has_flag(a, "rotate")) tell_running_provider(*running, dir, has_flag(a, "field"));
        const std::string name = local_host_name();
        const std::string url =
            pairing_url(host, port, token, identity.fingerprint, is_loopback(host) || host == name ? "" : name);
        if (!has_flag(a, "no-qr")) std::cout << qr_text(url);
        std::cout << url << "\n";
    } catch (const std::exception& e) {
        std::cerr << "umf-provider: " << e.what() << "\n";
        return kConfigError;
    }
    return kOk;
}

int run_share(const cli::Args& a) {
    using json = nlohmann::json;
    json request;
    if (has_flag(a, "list")) {
        request = {{"cmd", "list"}};
    } else if (auto id = get(a, "remove")) {
        request = {{"cmd", "unshare"}, {"id", cli::to_integer("remove", *id, 1, 1 << 30)}};
    } else {
        if (a.positional.size() != 1) throw UsageError("share takes one FILE or URL");
        const std::string what = a.positional[0];
        const auto rect_text = get(a, "rect");
        if (!rect_text) throw UsageError("share needs --rect x,y,width,height (screen pixels)");
        json rect = json::array();
        std::size_t start = 0;
        for (int i = 0; i < 4; ++i) {
            const auto comma = rect_text->find(',', start);
            if ((i < 3) != (comma != std::string::npos)) throw UsageError("--rect takes x,y,width,height");
            rect.push_back(cli::to_integer("rect", rect_text->substr(start, comma - start), -65536, 65536));
            start = comma + 1;
        }
        request = {{"cmd", "share"}, {"rect", rect}};
        if (what.rfind("http://", 0) == 0 || what.rfind("https://", 0) == 0) {
            request["url"] = what;
        } else {
            std::error_code ec;
            const auto file = std::filesystem::absolute(what, ec);
            if (ec || !std::filesystem::is_regular_file(file, ec)) {
                std::cerr << "umf-provider: " << what << " is not a readable file\n";
                return kConfigError;
            }
            request["file"] = file.string();
        }
        if (auto title = get(a, "title")) request["title"] = *title;
        if (auto screen = get(a, "screen")) request["screen"] = cli::to_integer("screen", *screen, 0, 15);
    }
    std::string answer;
    try {
        answer = control_request(control_socket_path(running_provider_port(a).value_or(kDefaultPort)), request.dump());
    } catch (const std::exception& e) {
        std::cerr << "umf-provider: " << e.what() << "\n";
        return kServeError;
    }
    std::cout << answer << "\n";
    const json parsed = json::parse(answer, nullptr, false);
    return parsed.is_object() && parsed.value("ok", false) ? kOk : kConfigError;
}

namespace {

std::string age_text(long long seconds) {
    if (seconds < 60) return std::to_string(seconds) + " s";
    return std::to_string(seconds / 60) + " min " + std::to_string(seconds % 60) + " s";
}

// The waiting puts as a table, one line each.
void print_put_table(const nlohmann::json& puts, std::ostream& out) {
    if (puts.empty()) {
        out << "no puts are waiting for an answer\n";
        return;
    }
    std::vector<std::vector<std::string>> rows{{"ID", "KIND", "WHAT", "SIZE", "FROM", "AGE"}};
    for (const auto& p : puts) {
        const bool url = p.value("kind", "") == "url";
        std::string what = url ? p.value("url", "") : p.value("name", "");
        if (url && !p.value("title", "").empty()) what = p.value("title", "") + " <" + what + ">";
        rows.push_back({std::to_string(p.value("id", 0ull)), p.value("kind", ""), printable_text(what),
                        url ? "-" : human_size(p.value("size", 0ll)), printable_text(p.value("client", "")),
                        age_text(p.value("age_s", 0ll))});
    }
    // Columns as wide as their widest cell (in bytes: names are mostly ASCII),
    // the last one unpadded.
    std::vector<std::size_t> width(rows[0].size(), 0);
    for (const auto& row : rows)
        for (std::size_t c = 0; c < row.size(); ++c) width[c] = std::max(width[c], row[c].size());
    for (const auto& row : rows) {
        std::string line;
        for (std::size_t c = 0; c < row.size(); ++c) {
            line += row[c];
            if (c + 1 < row.size()) line += std::string(width[c] - row[c].size() + 2, ' ');
        }
        out << line << "\n";
    }
}

}  // namespace

int run_puts(const cli::Args& a, std::ostream& out, std::ostream& err) {
    using json = nlohmann::json;
    const auto accept = get(a, "accept");
    const auto dismiss = get(a, "dismiss");
    if (accept && dismiss) throw UsageError("puts takes --accept ID or --dismiss ID, not both");
    if (!accept && (has_flag(a, "open") || has_flag(a, "always")))
        throw UsageError("--open and --always go with --accept ID");
    if (!a.positional.empty()) throw UsageError("puts takes no words; --accept ID or --dismiss ID answers one");
    json request;
    if (accept || dismiss) {
        const auto id = cli::to_integer(accept ? "accept" : "dismiss", accept ? *accept : *dismiss, 1,
                                        (1ll << 53) - 1);
        request = {{"cmd", "put_answer"},
                   {"id", id},
                   {"answer", dismiss ? "dismiss" : has_flag(a, "open") ? "open" : "save"},
                   {"always", has_flag(a, "always")}};
    } else {
        request = {{"cmd", "puts"}};
    }
    const ControlAnswer answer = ask_running_provider(running_provider_port(a).value_or(kDefaultPort), request, err);
    if (answer.exit != kOk) return answer.exit;
    const json& parsed = answer.json;
    if (has_flag(a, "json")) {
        out << answer.text << "\n";
        return kOk;
    }
    if (parsed.contains("puts") && parsed["puts"].is_array()) {
        print_put_table(parsed["puts"], out);
    } else {
        const std::string what = printable_text(parsed.value("name", std::string()));
        const std::string how = parsed.value("answer", std::string());
        out << "put " << parsed.value("id", 0ull) << (what.empty() ? "" : " (" + what + ")") << ": "
            << (how == "dismiss" ? "dismissed" : how == "open" ? "accepted, to be opened" : "accepted")
            << (request.value("always", false) ? "; its device's puts are accepted from now on" : "") << "\n";
    }
    return kOk;
}

}  // namespace umf::provider
