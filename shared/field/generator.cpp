#include "shared/field/generator.hpp"

#include <algorithm>
#include <chrono>
#include <memory>
#include <stdexcept>
#include <thread>
#include <vector>

#include "shared/field/contrast_polish.hpp"
#include "shared/field/sequential_search.hpp"
#include "shared/field/window_classes.hpp"

namespace umf {

namespace {

// Attempts per chain between synchronisation points: a few tenths of a second,
// so progress, stop requests and time limits are noticed quickly.
constexpr std::uint64_t kRoundAttempts = 1u << 21;

void check_options(const GeneratorOptions& o) {
    Field shape = make_field(std::max(o.width, 0), std::max(o.height, 0), o.window, o.colors, o.key);
    if (o.width <= 0 || o.height <= 0)
        throw std::invalid_argument("width and height must be positive");
    if (auto problem = describe_invalid(shape); !problem.empty()) throw std::invalid_argument(problem);
    if (o.chains < 1 || o.chains > 256) throw std::invalid_argument("chains must be 1..256");
    double bound = window_count_bound(o.window, o.colors, o.key);
    if (static_cast<double>(shape.window_count()) > bound)
        throw std::invalid_argument("a " + std::to_string(o.width) + " x " + std::to_string(o.height) + " field has " +
                                    std::to_string(shape.window_count()) +
                                    " windows, more than the counting bound allows (" +
                                    std::to_string(static_cast<long long>(bound)) + ")");
}

// splitmix64: independent, well-mixed seeds for the chains from one seed.
std::uint64_t chain_seed(std::uint64_t seed, int chain) {
    std::uint64_t z = seed + 0x9e3779b97f4a7c15ull * static_cast<std::uint64_t>(chain + 1);
    z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ull;
    z = (z ^ (z >> 27)) * 0x94d049bb133111ebull;
    return z ^ (z >> 31);
}

}  // namespace

GeneratorResult generate_field(const GeneratorOptions& o, const ProgressCallback& progress,
                               const std::atomic<bool>* stop) {
    check_options(o);
    using clock = std::chrono::steady_clock;
    const auto start = clock::now();
    auto elapsed = [&] { return std::chrono::duration<double>(clock::now() - start).count(); };

    Field shape = make_field(o.width, o.height, o.window, o.colors, o.key,
                             o.id.empty() ? default_field_id(o.width, o.height, o.window, o.colors, o.key) + "-s" +
                                                std::to_string(o.seed)
                                          : o.id);
    WindowCodec codec(o.window, o.colors, o.key);
    WindowClasses classes(codec);

    std::vector<std::unique_ptr<SequentialSearch>> chains;
    for (int i = 0; i < o.chains; ++i)
        chains.push_back(std::make_unique<SequentialSearch>(shape, classes, chain_seed(o.seed, i)));
    int threads = o.threads > 0 ? o.threads : static_cast<int>(std::max(1u, std::thread::hardware_concurrency()));
    threads = std::min(threads, o.chains);

    GeneratorResult result;
    int winner = -1;
    while (winner < 0) {
        // One round: every chain gets the same budget; chains are handed out
        // to the threads in turn.
        std::atomic<int> next{0};
        auto work = [&] {
            for (int i = next++; i < o.chains; i = next++) chains[i]->run(kRoundAttempts);
        };
        std::vector<std::thread> pool;
        for (int t = 1; t < threads; ++t) pool.emplace_back(work);
        work();
        for (auto& t : pool) t.join();

        GeneratorProgress p;
        p.elapsed_s = elapsed();
        p.windows_total = shape.window_count();
        for (int i = 0; i < o.chains; ++i) {
            const auto& c = *chains[i];
            p.attempts += c.attempts();
            p.jumps += c.jumps();
            p.windows_placed = std::max(p.windows_placed, c.best_windows_placed());
            if (winner < 0 && c.complete()) winner = i;
        }
        p.attempts_per_s = p.elapsed_s > 0 ? p.attempts / p.elapsed_s : 0;
        result.attempts = p.attempts;
        if (progress) progress(p);
        if (winner >= 0) break;
        bool all_exhausted = std::all_of(chains.begin(), chains.end(), [](auto& c) { return c->exhausted(); });
        if (all_exhausted) throw std::runtime_error("no 4-orientable field of this size exists from these seeds");
        if (stop && stop->load()) {
            result.stopped = true;
            break;
        }
        if (o.time_limit_s > 0 && p.elapsed_s >= o.time_limit_s) {
            result.timed_out = true;
            break;
        }
    }

    if (winner >= 0) {
        result.complete = true;
        result.winning_chain = winner;
        result.field = chains[winner]->best_field();
        long steps = o.contrast_steps >= 0 ? o.contrast_steps : 40L * o.width * o.height;
        polish_contrast(result.field, classes, steps, chain_seed(o.seed, -1));
    } else {
        // The deepest partial field over all chains, for the caller to keep.
        int best = 0;
        for (int i = 1; i < o.chains; ++i)
            if (chains[i]->best_windows_placed() > chains[best]->best_windows_placed()) best = i;
        result.field = chains[best]->best_field();
        result.winning_chain = best;
    }
    result.seconds = elapsed();
    return result;
}

}  // namespace umf
