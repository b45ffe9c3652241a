#include "shared/field/contrast_polish.hpp"

#include <algorithm>
#include <random>
#include <vector>

#include "shared/field/contrast.hpp"

namespace umf {

namespace {

int local_score(const Field& f, int r, int c) {
    int v = f.at(r, c), s = 0;
    if (c > 0) s += edge_score(v, f.at(r, c - 1), f.colors);
    if (c + 1 < f.width) s += edge_score(v, f.at(r, c + 1), f.colors);
    if (r > 0) s += edge_score(v, f.at(r - 1, c), f.colors);
    if (r + 1 < f.height) s += edge_score(v, f.at(r + 1, c), f.colors);
    return s;
}

}  // namespace

long polish_contrast(Field& f, const WindowClasses& classes, long steps, std::uint64_t seed) {
    if (f.colors < 3) return 0;
    const WindowCodec& codec = classes.codec();
    const int n = f.window, rows = f.window_rows(), cols = f.window_cols();
    ClassSet used(codec.code_space());
    std::vector<std::uint64_t> cls(static_cast<std::size_t>(rows) * cols);
    for (int r = 0; r < rows; ++r)
        for (int c = 0; c < cols; ++c) {
            cls[r * cols + c] = classes.of(codec.code_at(f, r, c)).id;
            used.insert(cls[r * cols + c]);
        }

    std::mt19937_64 rng(seed);
    std::vector<int> touched;
    std::vector<std::uint64_t> fresh;
    long changes = 0;
    for (long s = 0; s < steps; ++s) {
        const int r = static_cast<int>(rng() % f.height), c = static_cast<int>(rng() % f.width);
        const std::uint8_t old = f.at(r, c);
        const std::uint8_t v = static_cast<std::uint8_t>((old + 1 + rng() % (f.colors - 1)) % f.colors);
        const int before = local_score(f, r, c);
        f.at(r, c) = v;
        const int after = local_score(f, r, c);
        // Equal scores are accepted half the time so the search drifts across plateaus.
        if (after < before || (after == before && (rng() & 1))) {
            f.at(r, c) = old;
            continue;
        }
        touched.clear();
        for (int wr = std::max(0, r - n + 1); wr <= std::min(r, rows - 1); ++wr)
            for (int wc = std::max(0, c - n + 1); wc <= std::min(c, cols - 1); ++wc) touched.push_back(wr * cols + wc);
        for (int w : touched) used.erase(cls[w]);
        fresh.clear();
        bool ok = true;
        for (int w : touched) {
            auto k = classes.of(codec.code_at(f, w / cols, w % cols));
            if (k.self_symmetric || used.contains(k.id)) {
                ok = false;
                break;
            }
            used.insert(k.id);
            fresh.push_back(k.id);
        }
        if (ok) {
            for (std::size_t i = 0; i < touched.size(); ++i) cls[touched[i]] = fresh[i];
            ++changes;
            continue;
        }
        for (auto id : fresh) used.erase(id);
        for (int w : touched) used.insert(cls[w]);
        f.at(r, c) = old;
    }
    return changes;
}

}  // namespace umf
