// umf_overlay_latency: how long from an aim message to the focus region
// moving on screen (docs/BENCHMARKS.md, "Overlay"). A real provider with the
// overlay in focus mode on Xvfb with xcompmgr; a pinned TLS WebSocket client
// aims alternately at two places far apart, and the screen (XGetImage on the
// root window, as a screen grab sees it) is polled until the field shows at
// the new place. Usage: umf_overlay_latency [--aims N]. Needs Xvfb and
// xcompmgr; prints a Markdown table.
#include <algorithm>
#include <boost/asio/connect.hpp>
#include <boost/asio/ip/tcp.hpp>
#include <boost/asio/ssl.hpp>
#include <boost/beast/core.hpp>
#include <boost/beast/ssl.hpp>
#include <boost/beast/websocket.hpp>
#include <boost/beast/websocket/ssl.hpp>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <iostream>
#include <regex>
#include <string>
#include <thread>
#include <vector>

#include "provider/desktop/x11/x11_desktop.hpp"
#include "provider/service/pairing.hpp"
#include "provider/trust/tls_identity_store.hpp"
#include "shared/protocol/messages.hpp"
#include "tests/support/pinned_client.hpp"
#include "tests/support/temp_dir.hpp"
#include "tests/support/x11_session.hpp"

namespace {

namespace beast = boost::beast;
namespace net = boost::asio;
namespace ssl = net::ssl;
namespace websocket = beast::websocket;
namespace p = umf::protocol;
using namespace umf::test;
using Clock = std::chrono::steady_clock;
using Ms = std::chrono::duration<double, std::milli>;

// The provider's port from its log, once it listens.
int wait_for_port(const fs::path& log, Clock::duration timeout) {
    const std::regex listening(R"(listening on https://[^:]+:(\d+))");
    const auto deadline = Clock::now() + timeout;
    while (Clock::now() < deadline) {
        std::ifstream in(log);
        const std::string text(std::istreambuf_iterator<char>(in), {});
        std::smatch m;
        if (std::regex_search(text, m, listening)) return std::stoi(m[1]);
        std::this_thread::sleep_for(std::chrono::milliseconds(50));
    }
    return 0;
}

struct Probe {
    int x, y;
    std::uint32_t baseline;
};

bool changed(std::uint32_t a, std::uint32_t b) {
    for (int shift : {0, 8, 16})
        if (std::abs(static_cast<int>((a >> shift) & 255) - static_cast<int>((b >> shift) & 255)) > 12) return true;
    return false;
}

double percentile(std::vector<double> v, double q) {
    std::sort(v.begin(), v.end());
    return v[static_cast<std::size_t>(std::min<double>(v.size() - 1, std::floor(q * (v.size() - 1) + 0.5)))];
}

}  // namespace

int main(int argc, char** argv) {
    int aims = 40;
    for (int i = 1; i + 1 < argc; ++i)
        if (std::string(argv[i]) == "--aims") aims = std::max(2, std::atoi(argv[i + 1]));
    for (const char* program : {"Xvfb", "xcompmgr"})
        if (!find_program(program)) {
            std::cerr << "umf_overlay_latency: " << program << " is not installed\n";
            return 2;
        }
    TempDir dir;
    const XServer server = start_xvfb(dir.path / "xvfb.log", "1920x1080x24");
    Process::Options options;
    options.env = environment_with({{"DISPLAY", server.display}, {"QT_QPA_PLATFORM", "xcb"}});
    options.log = dir.path / "xcompmgr.log";
    Process xcompmgr({"xcompmgr"}, options);
    std::this_thread::sleep_for(std::chrono::milliseconds(500));

    const fs::path config = dir.path / "config";
    const auto identity = umf::provider::load_or_create_tls_identity(config);
    const std::string token = umf::provider::load_or_create_token(config);
    options.log = dir.path / "provider.log";
    Process provider({UMF_PROVIDER_TOOL, "serve", "--config-dir", config.string(), "--port", "0", "--no-qr",
                      "--region", "focus", "--focus-radius", "4", "--activation", "always", "--period", "0",
                      "--opacity-min", "0.6", "--opacity-max", "0.6"},
                     options);
    const int port = wait_for_port(dir.path / "provider.log", std::chrono::seconds(15));
    if (port == 0) {
        std::ifstream in(dir.path / "provider.log");
        std::cerr << "umf_overlay_latency: the provider did not start:\n" << std::string(std::istreambuf_iterator<char>(in), {});
        return 1;
    }
    std::this_thread::sleep_for(std::chrono::milliseconds(500));
    const umf::provider::X11Desktop desktop(server.display);

    net::io_context io;
    ssl::context tls = pinned_client_context(identity.fingerprint);
    websocket::stream<beast::ssl_stream<beast::tcp_stream>> ws(io, tls);
    beast::get_lowest_layer(ws).connect(net::ip::tcp::endpoint(net::ip::make_address("127.0.0.1"), port));
    ws.next_layer().handshake(ssl::stream_base::client);
    ws.handshake("127.0.0.1:" + std::to_string(port), "/ws");
    ws.write(net::buffer(p::encode(p::Hello{p::RequestId{std::int64_t{1}}, token, "umf_overlay_latency"})));
    beast::flat_buffer buffer;
    ws.read(buffer);
    const auto parsed = p::parse_message(beast::buffers_to_string(buffer.data()), p::kRequesterLimits);
    const auto* welcome = std::get_if<p::Message>(&parsed) ? std::get_if<p::Welcome>(&std::get<p::Message>(parsed)) : nullptr;
    if (!welcome || welcome->field.screens.empty()) {
        std::cerr << "umf_overlay_latency: no welcome\n";
        return 1;
    }
    // Screen pixel <-> field point through the first screen's region.
    const auto& screen = welcome->field.screens[0];
    const double module_px = screen.width_px / (screen.region.u1 - screen.region.u0);
    auto field_point = [&](double x, double y) {
        return p::FieldPoint{screen.region.u0 + x / module_px, screen.region.v0 + y / module_px};
    };
    // Two places far apart; probes on module centres around each.
    const std::pair<int, int> places[2] = {{480, 540}, {1440, 540}};
    std::vector<Probe> probes[2];
    for (int k = 0; k < 2; ++k)
        for (int dy = -1; dy <= 1; ++dy)
            for (int dx = -1; dx <= 1; ++dx) {
                const int x = places[k].first + static_cast<int>(dx * module_px),
                          y = places[k].second + static_cast<int>(dy * module_px);
                const auto shot = desktop.capture({x, y, 1, 1});
                probes[k].push_back({x, y, shot.pixels.empty() ? 0u : shot.pixels[0]});
            }

    std::vector<double> latencies;
    int missed = 0;
    for (int i = 0; i < aims; ++i) {
        const int k = i % 2;
        const p::FieldPoint point = field_point(places[k].first, places[k].second);
        const auto start = Clock::now();
        ws.write(net::buffer(p::encode(p::Aim{p::RequestId{std::int64_t{i + 2}}, point, 0.95})));
        bool shown = false;
        while (!shown && Clock::now() - start < std::chrono::seconds(2)) {
            for (const Probe& probe : probes[k]) {
                const auto shot = desktop.capture({probe.x, probe.y, 1, 1});
                if (!shot.pixels.empty() && changed(shot.pixels[0], probe.baseline)) {
                    shown = true;
                    break;
                }
            }
        }
        if (shown)
            latencies.push_back(Ms(Clock::now() - start).count());
        else
            ++missed;
        ws.read(buffer);  // the target
        buffer.consume(buffer.size());
        // The other place's circle must be gone before it is timed again.
        std::this_thread::sleep_for(std::chrono::milliseconds(250));
    }
    ws.close(websocket::close_code::normal);
    if (latencies.empty()) {
        std::cerr << "umf_overlay_latency: the focus region never showed (" << missed << " aims)\n";
        return 1;
    }
    std::printf("| aims | shown | p50 ms | p95 ms | max ms |\n|---|---|---|---|---|\n");
    std::printf("| %d | %zu | %.1f | %.1f | %.1f |\n", aims, latencies.size(), percentile(latencies, 0.5),
                percentile(latencies, 0.95), *std::max_element(latencies.begin(), latencies.end()));
    return missed == 0 ? 0 : 1;
}
