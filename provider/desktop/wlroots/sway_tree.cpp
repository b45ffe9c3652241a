#include "provider/desktop/wlroots/sway_tree.hpp"

#include "provider/common/json_fields.hpp"

#include <functional>
#include <string>

namespace umf::provider {

namespace {

using nlohmann::json;

WindowRect rect_of(const json& node, const char* key) {
    const auto it = node.find(key);
    if (it == node.end() || !it->is_object()) return {};
    return {it->value("x", 0), it->value("y", 0), it->value("width", 0), it->value("height", 0)};
}

const json& children(const json& node, const char* key) {
    static const json none = json::array();
    const auto it = node.find(key);
    return it != node.end() && it->is_array() ? *it : none;
}

// A view: a container that shows a client (it has a process, or at least
// an app id or an X11 window), not a split of others.
bool is_view(const json& node) {
    const std::string type = json_text(node, "type");
    return (type == "con" || type == "floating_con") && children(node, "nodes").empty() &&
           children(node, "floating_nodes").empty() &&
           (node.contains("pid") || node.contains("app_id") || node.contains("window_properties"));
}

WindowInfo window_of(const json& node, const std::string& output) {
    WindowInfo window;
    window.id = node.value("id", 0ul);
    const WindowRect content = rect_of(node, "rect");
    const WindowRect title = rect_of(node, "deco_rect");
    window.rect = {content.x, content.y - title.height, content.width, content.height + title.height};
    window.title = json_text(node, "name");
    window.wm_class = json_text(node, "app_id");
    if (const auto props = node.find("window_properties"); props != node.end() && props->is_object()) {
        // An Xwayland window: its WM_CLASS.
        window.wm_class = json_text(*props, "class");
        window.instance = json_text(*props, "instance");
    }
    if (const auto pid = node.find("pid"); pid != node.end() && pid->is_number_integer()) window.pid = pid->get<int>();
    window.output = output;
    return window;
}

void each_view(const json& node, const std::function<void(const json&)>& visit) {
    if (is_view(node)) visit(node);
    for (const auto& child : children(node, "nodes")) each_view(child, visit);
    for (const auto& child : children(node, "floating_nodes")) each_view(child, visit);
}

bool shown(const json& view) { return view.value("visible", true); }

int fullscreen_mode(const json& node) {
    const auto it = node.find("fullscreen_mode");
    return it != node.end() && it->is_number_integer() ? it->get<int>() : 0;
}

// One visible workspace's views, top-most first.
void workspace_windows(const json& workspace, const std::string& output, std::vector<WindowInfo>& out) {
    std::vector<WindowInfo> fullscreen, floating, tiled;
    for (const auto& child : children(workspace, "nodes"))
        each_view(child, [&](const json& v) {
            if (!shown(v)) return;
            (fullscreen_mode(v) == 1 ? fullscreen : tiled).push_back(window_of(v, output));
        });
    const auto& floats = children(workspace, "floating_nodes");
    for (auto it = floats.rbegin(); it != floats.rend(); ++it)
        each_view(*it, [&](const json& v) {
            if (!shown(v)) return;
            (fullscreen_mode(v) == 1 ? fullscreen : floating).push_back(window_of(v, output));
        });
    for (auto* part : {&fullscreen, &floating, &tiled}) out.insert(out.end(), part->begin(), part->end());
}

}  // namespace

std::vector<WindowInfo> sway_visible_windows(const nlohmann::json& tree) {
    std::vector<WindowInfo> global_fullscreen, rest;
    for (const auto& output : children(tree, "nodes")) {
        const std::string output_name = json_text(output, "name");
        if (output_name == "__i3") continue;  // the scratchpad
        const std::string current = json_text(output, "current_workspace");
        for (const auto& workspace : children(output, "nodes")) {
            if (json_text(workspace, "type") != "workspace") continue;
            if (!current.empty() && json_text(workspace, "name") != current) continue;
            std::vector<WindowInfo> windows;
            workspace_windows(workspace, output_name, windows);
            rest.insert(rest.end(), windows.begin(), windows.end());
        }
    }
    // Fullscreen on the whole layout: above every output's windows.
    each_view(tree, [&](const json& v) {
        if (fullscreen_mode(v) == 2 && shown(v)) global_fullscreen.push_back(window_of(v, {}));
    });
    global_fullscreen.insert(global_fullscreen.end(), rest.begin(), rest.end());
    return global_fullscreen;
}

std::vector<unsigned long> sway_window_ids(const nlohmann::json& tree) {
    std::vector<unsigned long> ids;
    each_view(tree, [&](const json& v) { ids.push_back(v.value("id", 0ul)); });
    return ids;
}

std::optional<WindowInfo> sway_window(const nlohmann::json& tree, unsigned long id) {
    std::optional<WindowInfo> found;
    for (const auto& output : children(tree, "nodes"))
        each_view(output, [&](const json& v) {
            if (!found && v.value("id", 0ul) == id) found = window_of(v, json_text(output, "name"));
        });
    return found;
}

std::optional<unsigned long> sway_focused_window(const nlohmann::json& tree) {
    std::optional<unsigned long> found;
    each_view(tree, [&](const json& v) {
        if (v.value("focused", false)) found = v.value("id", 0ul);
    });
    return found;
}

std::vector<DesktopOutput> sway_outputs(const nlohmann::json& outputs) {
    std::vector<DesktopOutput> out;
    if (!outputs.is_array()) return out;
    for (const auto& output : outputs) {
        if (!output.is_object() || !output.value("active", false)) continue;
        DesktopOutput o;
        o.name = json_text(output, "name");
        o.rect = rect_of(output, "rect");
        if (const auto scale = output.find("scale"); scale != output.end() && scale->is_number()) o.scale = scale->get<double>();
        if (!o.rect.empty()) out.push_back(std::move(o));
    }
    return out;
}

std::optional<WindowInfo> topmost_window_at(const std::vector<WindowInfo>& top_first, double x, double y,
                                            const WindowFilter& filter) {
    for (const auto& window : top_first)
        if (window.rect.contains(x, y) && !filter.skips(window)) return window;
    return std::nullopt;
}

}  // namespace umf::provider
