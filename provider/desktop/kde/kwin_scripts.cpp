#include "provider/desktop/kde/kwin_scripts.hpp"

#include <QJsonArray>
#include <QJsonDocument>
#include <QJsonObject>
#include <QJsonValue>
#include <algorithm>
#include <cmath>
#include <cstdio>

namespace umf::provider {

namespace {

// Shared by every script: the window list of either KWin and whether a
// window is on the desktop shown now.
constexpr const char* kPrelude = R"JS(
function umfWindows() {
    return workspace.windowList ? workspace.windowList() : workspace.clientList();
}
function umfOnCurrentDesktop(w) {
    if (w.onAllDesktops) return true;
    var current = workspace.currentDesktop;
    if (typeof current === "number") return w.desktop === current || w.desktop === -1;
    var desktops = w.desktops || [];
    for (var i = 0; i < desktops.length; ++i)
        if (desktops[i] === current || (desktops[i] && current && desktops[i].id === current.id)) return true;
    return desktops.length === 0;
}
)JS";

int rounded(const QJsonValue& value) { return static_cast<int>(std::lround(value.toDouble())); }

long overlap(const WindowRect& a, const WindowRect& b) {
    const long w = std::min(a.x + a.width, b.x + b.width) - std::max(a.x, b.x);
    const long h = std::min(a.y + a.height, b.y + b.height) - std::max(a.y, b.y);
    return w > 0 && h > 0 ? w * h : 0;
}

}  // namespace

std::string js_string(const std::string& text) {
    std::string out = "\"";
    for (const char c : text) {
        const auto byte = static_cast<unsigned char>(c);
        if (c == '"' || c == '\\') {
            out += '\\';
            out += c;
        } else if (byte < 0x20) {
            char escaped[8];
            std::snprintf(escaped, sizeof escaped, "\\u%04x", byte);
            out += escaped;
        } else {
            out += c;
        }
    }
    // U+2028 and U+2029 end a line in older JavaScript string literals.
    for (const std::string separator : {"\xe2\x80\xa8", "\xe2\x80\xa9"})
        for (auto at = out.find(separator); at != std::string::npos; at = out.find(separator, at))
            out.replace(at, separator.size(), separator == "\xe2\x80\xa8" ? "\\u2028" : "\\u2029");
    return out + "\"";
}

std::string list_windows_script() {
    return std::string(kPrelude) + R"JS(
(function () {
    var list = umfWindows();
    var out = [];
    for (var i = 0; i < list.length; ++i) {
        var w = list[i];
        if (!w || w.deleted || w.minimized || !(w.normalWindow || w.dialog) || !umfOnCurrentDesktop(w)) continue;
        var g = w.frameGeometry;
        out.push({uuid: String(w.internalId), stacking: w.stackingOrder, x: g.x, y: g.y, width: g.width,
                  height: g.height, caption: String(w.caption), resourceClass: String(w.resourceClass),
                  resourceName: String(w.resourceName), pid: w.pid, x11: !!w.windowId});
    }
    umfAnswer(JSON.stringify(out));
})();
)JS";
}

std::string move_window_script(const std::string& uuid, const WindowRect& rect) {
    return std::string(kPrelude) + "var umfUuid = " + js_string(uuid) + ";\nvar umfRect = {x: " +
           std::to_string(rect.x) + ", y: " + std::to_string(rect.y) + ", width: " + std::to_string(rect.width) +
           ", height: " + std::to_string(rect.height) + "};\n" + R"JS(
(function () {
    var list = umfWindows();
    for (var i = 0; i < list.length; ++i) {
        if (String(list[i].internalId) !== umfUuid) continue;
        list[i].frameGeometry = umfRect;
        umfAnswer("moved");
        return;
    }
    umfAnswer("missing");
})();
)JS";
}

std::optional<std::vector<KWinWindow>> parse_window_list(const std::string& json) {
    QJsonParseError error{};
    const QJsonDocument document = QJsonDocument::fromJson(QByteArray::fromStdString(json), &error);
    if (error.error != QJsonParseError::NoError || !document.isArray()) return std::nullopt;
    std::vector<KWinWindow> windows;
    for (const QJsonValue& value : document.array()) {
        if (!value.isObject()) return std::nullopt;
        const QJsonObject o = value.toObject();
        if (!o.value("uuid").isString()) return std::nullopt;
        KWinWindow w;
        w.uuid = o.value("uuid").toString().toStdString();
        w.stacking = o.value("stacking").toInt();
        w.rect = {rounded(o.value("x")), rounded(o.value("y")), rounded(o.value("width")), rounded(o.value("height"))};
        w.caption = o.value("caption").toString().toStdString();
        w.resource_class = o.value("resourceClass").toString().toStdString();
        w.resource_name = o.value("resourceName").toString().toStdString();
        w.pid = o.value("pid").toInt();
        w.x11 = o.value("x11").toBool();
        windows.push_back(std::move(w));
    }
    return windows;
}

unsigned long window_id(const std::string& uuid) {
    // FNV-1a: the same uuid gives the same id in every process.
    std::uint64_t hash = 1469598103934665603ull;
    for (const char c : uuid) hash = (hash ^ static_cast<unsigned char>(c)) * 1099511628211ull;
    return static_cast<unsigned long>(hash);
}

WindowInfo to_window_info(const KWinWindow& window, const std::vector<DesktopOutput>& outputs) {
    WindowInfo info;
    info.id = window_id(window.uuid);
    info.rect = window.rect;
    info.title = window.caption;
    info.instance = window.x11 ? window.resource_name : std::string();
    info.wm_class = window.resource_class;
    info.pid = window.pid;
    long best = 0;
    for (const auto& output : outputs)
        if (const long area = overlap(window.rect, output.rect); area > best) {
            best = area;
            info.output = output.name;
        }
    return info;
}

std::optional<WindowInfo> window_at_point(const std::vector<KWinWindow>& windows, double x, double y,
                                          const WindowFilter& filter, const std::vector<DesktopOutput>& outputs) {
    std::vector<const KWinWindow*> stack;
    for (const auto& window : windows) stack.push_back(&window);
    std::stable_sort(stack.begin(), stack.end(), [](auto* a, auto* b) { return a->stacking > b->stacking; });
    for (const KWinWindow* window : stack) {
        if (!window->rect.contains(x, y)) continue;
        WindowInfo info = to_window_info(*window, outputs);
        if (!filter.skips(info)) return info;
    }
    return std::nullopt;
}

}  // namespace umf::provider
