#include "provider/desktop/window_placement.hpp"

#include <unistd.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <iterator>
#include <set>
#include <thread>

namespace umf::provider {

namespace {

int clamp_start(int start, int size, int lo, int room) {
    // Larger than the room: its top-left corner stays in view.
    return std::max(lo, std::min(start, lo + room - size));
}

std::optional<int> parent_of(int pid) {
    std::ifstream in("/proc/" + std::to_string(pid) + "/stat");
    const std::string stat{std::istreambuf_iterator<char>(in), {}};
    // "PID (COMM) STATE PPID ...": COMM may hold spaces and parentheses.
    const auto close = stat.rfind(')');
    if (close == std::string::npos) return std::nullopt;
    char state = 0;
    int parent = 0;
    if (std::sscanf(stat.c_str() + close + 1, " %c %d", &state, &parent) != 2) return std::nullopt;
    return parent;
}

}  // namespace

PlaceRect centred_on(int width, int height, double x, double y, const PlaceRect& screen) {
    PlaceRect out;
    out.width = width;
    out.height = height;
    out.x = clamp_start(static_cast<int>(std::lround(x - width / 2.0)), width, screen.x, screen.width);
    out.y = clamp_start(static_cast<int>(std::lround(y - height / 2.0)), height, screen.y, screen.height);
    return out;
}

std::optional<unsigned long> pick_new_window(const std::vector<unsigned long>& before,
                                             const std::vector<unsigned long>& now,
                                             const std::function<bool(unsigned long)>& from_child,
                                             const std::function<bool(unsigned long)>& normal) {
    const std::set<unsigned long> old(before.begin(), before.end());
    std::vector<unsigned long> fresh;
    for (unsigned long w : now)
        if (!old.count(w)) fresh.push_back(w);
    for (unsigned long w : fresh)
        if (from_child && from_child(w)) return w;
    for (unsigned long w : fresh)
        if (normal && normal(w)) return w;
    return std::nullopt;
}

bool descends_from(int pid, int ancestor) {
    if (ancestor <= 1) return false;
    // A bounded walk: a parent chain is short, and /proc can change under it.
    for (int step = 0; step < 64 && pid > 1; ++step) {
        if (pid == ancestor) return true;
        const auto parent = parent_of(pid);
        if (!parent) return false;
        pid = *parent;
    }
    return false;
}

}  // namespace umf::provider
