#include "provider/desktop/wlroots/hyprland_ipc.hpp"

#include "provider/common/json_fields.hpp"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <map>
#include <set>

#include "provider/desktop/wlroots/unix_socket.hpp"

namespace umf::provider {

namespace {

using nlohmann::json;

int pair_part(const json& node, const char* key, std::size_t i) {
    const auto it = node.find(key);
    return it != node.end() && it->is_array() && it->size() > i && (*it)[i].is_number() ? (*it)[i].get<int>() : 0;
}

int workspace_id(const json& node, const char* key) {
    const auto it = node.find(key);
    return it != node.end() && it->is_object() ? json_int(*it, "id", 0) : 0;
}

bool is_fullscreen(const json& client) {
    const auto it = client.find("fullscreen");
    if (it == client.end()) return false;
    // A bool before Hyprland 0.42, the fullscreen mode (0 none) since.
    return it->is_boolean() ? it->get<bool>() : it->is_number() && it->get<int>() != 0;
}

}  // namespace

std::string hyprland_socket_path(const std::string& signature, const std::string& runtime_dir) {
    if (!runtime_dir.empty()) {
        const auto path = std::filesystem::path(runtime_dir) / "hypr" / signature / ".socket.sock";
        std::error_code ec;
        if (std::filesystem::exists(path, ec)) return path.string();
    }
    return (std::filesystem::path("/tmp/hypr") / signature / ".socket.sock").string();
}

json hyprland_request(const std::string& socket_path, const std::string& request, std::chrono::milliseconds timeout) {
    UnixSocket socket(socket_path, std::chrono::steady_clock::now() + timeout);
    socket.write_all(request);
    auto reply = json::parse(socket.read_to_end(), nullptr, false);
    if (reply.is_discarded()) throw DesktopError("Hyprland answered '" + request + "' with malformed JSON");
    return reply;
}

std::vector<DesktopOutput> hyprland_outputs(const json& monitors) {
    std::vector<DesktopOutput> out;
    if (!monitors.is_array()) return out;
    for (const auto& m : monitors) {
        if (!m.is_object() || m.value("disabled", false)) continue;
        DesktopOutput o;
        o.name = json_text(m, "name");
        const auto scale = m.find("scale");
        o.scale = scale != m.end() && scale->is_number() && scale->get<double>() > 0 ? scale->get<double>() : 1.0;
        o.rect = {json_int(m, "x"), json_int(m, "y"), static_cast<int>(std::lround(json_int(m, "width") / o.scale)),
                  static_cast<int>(std::lround(json_int(m, "height") / o.scale))};
        // A turned monitor (transform 1, 3, 5, 7) lays out its height across.
        if (json_int(m, "transform") % 2 == 1) std::swap(o.rect.width, o.rect.height);
        if (!o.rect.empty()) out.push_back(std::move(o));
    }
    return out;
}

std::vector<WindowInfo> hyprland_visible_windows(const json& clients, const json& monitors) {
    std::map<int, std::string> shown_workspaces;  // workspace id -> monitor name
    std::map<int, std::string> monitor_names;
    if (monitors.is_array())
        for (const auto& m : monitors) {
            if (!m.is_object()) continue;
            monitor_names[json_int(m, "id", -1)] = json_text(m, "name");
            shown_workspaces[workspace_id(m, "activeWorkspace")] = json_text(m, "name");
            if (const int special = workspace_id(m, "specialWorkspace"); special != 0)
                shown_workspaces[special] = json_text(m, "name");
        }
    struct Ranked {
        int layer;  // 0 fullscreen, 1 floating, 2 tiled
        int focus_order;
        WindowInfo window;
    };
    std::vector<Ranked> ranked;
    if (clients.is_array())
        for (const auto& c : clients) {
            if (!c.is_object() || !c.value("mapped", true) || c.value("hidden", false)) continue;
            const auto shown = shown_workspaces.find(workspace_id(c, "workspace"));
            if (shown == shown_workspaces.end()) continue;
            WindowInfo w;
            const std::string address = json_text(c, "address");
            w.id = std::strtoul(address.c_str(), nullptr, 16);
            w.rect = {pair_part(c, "at", 0), pair_part(c, "at", 1), pair_part(c, "size", 0), pair_part(c, "size", 1)};
            w.title = json_text(c, "title");
            w.wm_class = json_text(c, "class");
            w.pid = json_int(c, "pid");
            const auto monitor = monitor_names.find(json_int(c, "monitor", -1));
            w.output = monitor != monitor_names.end() ? monitor->second : shown->second;
            const int layer = is_fullscreen(c) ? 0 : c.value("floating", false) ? 1 : 2;
            ranked.push_back({layer, json_int(c, "focusHistoryID", 1 << 20), std::move(w)});
        }
    std::stable_sort(ranked.begin(), ranked.end(), [](const Ranked& a, const Ranked& b) {
        return a.layer != b.layer ? a.layer < b.layer : a.focus_order < b.focus_order;
    });
    std::vector<WindowInfo> out;
    for (auto& r : ranked) out.push_back(std::move(r.window));
    return out;
}

}  // namespace umf::provider
