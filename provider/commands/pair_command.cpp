#include "commands/pair_command.hpp"

#include <filesystem>
#include <iostream>
#include <nlohmann/json.hpp>

#include "commands/common_options.hpp"
#include "server/control_socket.hpp"
#include "server/pairing.hpp"
#include "server/pairing_qr.hpp"
#include "server/tls_identity.hpp"

namespace umf::provider {

using cli::get;
using cli::has_flag;
using cli::UsageError;

int run_pair(const cli::Args& a) {
    const unsigned short port = port_option(a);
    const std::string host = url_host(a, "127.0.0.1");
    const auto dir = config_dir_option(a);
    try {
        const TlsIdentity identity = load_or_create_tls_identity(dir);
        const std::string token = load_or_create_token(dir, has_flag(a, "rotate"));
        const std::string url = pairing_url(host, port, token, identity.fingerprint);
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
        answer = control_request(control_socket_path(port_option(a)), request.dump());
    } catch (const std::exception& e) {
        std::cerr << "umf-provider: " << e.what() << "\n";
        return kServeError;
    }
    std::cout << answer << "\n";
    const json parsed = json::parse(answer, nullptr, false);
    return parsed.is_object() && parsed.value("ok", false) ? kOk : kConfigError;
}

}  // namespace umf::provider
