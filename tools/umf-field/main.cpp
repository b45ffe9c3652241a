// umf-field: generate, verify, render and describe marker fields.
#include <unistd.h>

#include <atomic>
#include <cmath>
#include <csignal>
#include <cstdio>
#include <cstring>
#include <iostream>
#include <map>
#include <nlohmann/json.hpp>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

#include "shared/cli/args.hpp"
#include "shared/field/contrast.hpp"
#include "shared/field/field_io.hpp"
#include "shared/field/generator.hpp"
#include "shared/field/render.hpp"
#include "shared/field/verifier.hpp"
#include "shared/io/atomic_file.hpp"

namespace {

enum FieldToolExit {
    kOk = 0,
    kNotOrientable = 1,  // verify found conflicts
    kUsage = 2,
    kFileError = 3,      // unreadable, malformed or unwritable file
    kIncomplete = 4,     // generate stopped or out of time; the partial field was saved
};

const char* kUsageText = R"(umf-field: make and check Uniform Marker Fields

usage:
  umf-field generate --width W --height H [--window N] [--colors K] [--key modules|edges]
                     [--seed S] [--chains C] [--threads T] [--time-limit SECONDS]
                     [--contrast-steps N] [--id ID] [--quiet] --out F.json
  umf-field verify F.json [--max-listed N]
  umf-field render F.json --out F.png|F.svg|F.pdf [--module-px P | --module-mm MM [--dpi D]]
                   [--quiet-zone Q] [--caption TEXT]
  umf-field info F.json [--json]
  umf-field help [COMMAND]

generate  synthesizes a 4-orientable field: every n x n window unique, rotations included.
          Binary fields (K = 2) use window 4 and module keys by default; K >= 3 uses
          window 3 and edge keys, and raises edge contrast once the field is valid.
          The result depends only on the seed and --chains (default 2), not on the
          machine. Progress goes to stderr. Ctrl-C (or --time-limit) stops and saves
          the deepest partial field to F.partial.json.
verify    proves a field 4-orientable, or lists every conflict.
render    draws a field as PNG, SVG or PDF; --module-mm gives a physical size for print.
          A screen's own field (its file names the screen) is captioned with the
          screen and the field's id unless --caption says otherwise ("" for none).
info      the field's shape, how full it is against the counting bound, its edge
          contrast and whether it verifies.

exit codes: 0 success; 1 the field is not 4-orientable; 2 wrong usage;
            3 a file could not be read, parsed or written; 4 generation stopped
            before completion (partial field saved).
)";

using umf::cli::Args;
using umf::cli::UsageError;
using umf::cli::get;
using umf::cli::has_flag;
using umf::cli::parse_args;
using umf::cli::to_integer;
using umf::cli::to_number;

std::string one_field_path(const Args& a, const char* command) {
    if (a.positional.size() != 1) throw UsageError(std::string(command) + " takes exactly one field file");
    return a.positional[0];
}

std::atomic<bool> g_stop{false};  // set from the signal handler; nothing else is global
extern "C" void on_interrupt(int) {
    g_stop = true;
    std::signal(SIGINT, SIG_DFL);  // a second Ctrl-C ends the program at once
}

std::string partial_path(const std::string& out) {
    std::string base = out;
    if (base.size() > 5 && base.compare(base.size() - 5, 5, ".json") == 0) base.resize(base.size() - 5);
    return base + ".partial.json";
}

int cmd_generate(const Args& a) {
    if (!a.positional.empty()) throw UsageError("generate takes no file argument; use --out F.json");
    umf::GeneratorOptions o;
    auto need = [&](const char* n) {
        auto v = get(a, n);
        if (!v) throw UsageError(std::string("generate needs --") + n);
        return *v;
    };
    o.width = static_cast<int>(to_integer("width", need("width"), 1, umf::kMaxFieldSide));
    o.height = static_cast<int>(to_integer("height", need("height"), 1, umf::kMaxFieldSide));
    std::string out = need("out");
    o.colors = static_cast<int>(to_integer("colors", get(a, "colors").value_or("2"), umf::kMinColors, umf::kMaxColors));
    o.window = static_cast<int>(to_integer("window", get(a, "window").value_or(o.colors == 2 ? "4" : "3"), 3, 4));
    o.key = umf::default_key(o.colors);
    if (auto k = get(a, "key")) {
        if (*k == "modules")
            o.key = umf::WindowKey::modules;
        else if (*k == "edges")
            o.key = umf::WindowKey::edges;
        else
            throw UsageError("--key must be modules or edges");
    }
    o.seed = static_cast<std::uint64_t>(to_integer("seed", get(a, "seed").value_or("1"), 0, 1LL << 62));
    o.chains = static_cast<int>(to_integer("chains", get(a, "chains").value_or("2"), 1, 256));
    o.threads = static_cast<int>(to_integer("threads", get(a, "threads").value_or("0"), 0, 256));
    o.time_limit_s = to_number("time-limit", get(a, "time-limit").value_or("0"), 0, 1e7);
    o.contrast_steps = to_integer("contrast-steps", get(a, "contrast-steps").value_or("-1"), -1, 1LL << 40);
    o.id = get(a, "id").value_or("");
    const bool quiet = has_flag(a, "quiet");
    const bool tty = isatty(STDERR_FILENO);

    double last_line = -1;
    long deepest = -1;
    double deepest_at = 0;
    bool hinted = false;
    auto progress = [&](const umf::GeneratorProgress& p) {
        if (p.windows_placed > deepest) {
            deepest = p.windows_placed;
            deepest_at = p.elapsed_s;
        }
        if (quiet) return;
        if (!hinted && p.elapsed_s - deepest_at > 60) {
            hinted = true;
            std::fprintf(stderr,
                         "%sumf-field: no progress for a minute: this size may be beyond what the generator "
                         "reaches (binary 4 x 4 fields stall near half the counting bound). Ctrl-C keeps the "
                         "partial field.\n",
                         tty ? "\n" : "");
        }
        if (!tty && p.elapsed_s - last_line < 10) return;  // a log file gets a line every 10 s
        last_line = p.elapsed_s;
        std::fprintf(stderr, "%s%7.1f s  windows %ld/%ld  left %ld  %.2f M tries/s  restarts %llu%s",
                     tty ? "\r" : "", p.elapsed_s, p.windows_placed, p.windows_total, p.conflicts_left(),
                     p.attempts_per_s / 1e6, static_cast<unsigned long long>(p.jumps), tty ? "   " : "\n");
        std::fflush(stderr);
    };

    std::signal(SIGINT, on_interrupt);
    std::signal(SIGTERM, on_interrupt);
    umf::GeneratorResult r = umf::generate_field(o, progress, &g_stop);
    if (!quiet && tty) std::fputc('\n', stderr);

    if (!r.complete) {
        std::string p = partial_path(out);
        umf::save_field(r.field, p);
        auto report = umf::verify_field(r.field);
        std::fprintf(stderr, "umf-field: %s after %.1f s; the deepest partial field (%zu conflicts) is in %s\n",
                     r.stopped ? "stopped" : "time limit reached", r.seconds, report.conflicts.size(), p.c_str());
        return kIncomplete;
    }
    // Never write a field that does not verify.
    auto report = umf::verify_field(r.field);
    if (!report.orientable())
        throw std::logic_error("generated field failed verification: " + umf::describe(report.conflicts.front()));
    umf::save_field(r.field, out);
    std::printf("%s: %d x %d, window %d, %d colours, key %s, %ld windows, verified, %.2f s\n", out.c_str(),
                r.field.width, r.field.height, r.field.window, r.field.colors, umf::to_string(r.field.key),
                r.field.window_count(), r.seconds);
    return kOk;
}

int cmd_verify(const Args& a) {
    std::string path = one_field_path(a, "verify");
    long max_listed = to_integer("max-listed", get(a, "max-listed").value_or("50"), 0, 1LL << 40);
    umf::Field f = umf::load_field(path);
    auto report = umf::verify_field(f);
    if (report.orientable()) {
        std::printf("%s: 4-orientable (%ld windows of %d x %d, key %s)\n", path.c_str(), report.windows, f.window,
                    f.window, umf::to_string(f.key));
        return kOk;
    }
    std::printf("%s: NOT 4-orientable: %zu conflicts among %ld windows\n", path.c_str(), report.conflicts.size(),
                report.windows);
    long shown = 0;
    for (const auto& c : report.conflicts) {
        if (shown++ >= max_listed) {
            std::printf("  ... and %ld more (--max-listed N shows more)\n",
                        static_cast<long>(report.conflicts.size()) - max_listed);
            break;
        }
        std::printf("  %s\n", umf::describe(c).c_str());
    }
    return kNotOrientable;
}

int cmd_render(const Args& a) {
    std::string path = one_field_path(a, "render");
    auto out = get(a, "out");
    if (!out) throw UsageError("render needs --out F.png|F.svg|F.pdf");
    umf::ImageFormat format;
    try {
        format = umf::image_format_for_path(*out);
    } catch (const std::invalid_argument& e) {
        throw UsageError(e.what());
    }
    umf::RenderOptions ro;
    if (auto v = get(a, "module-px")) ro.module_px = static_cast<int>(to_integer("module-px", *v, 1, 4096));
    if (auto v = get(a, "module-mm")) ro.module_mm = to_number("module-mm", *v, 0.01, 10000);
    if (auto v = get(a, "dpi")) ro.dpi = to_number("dpi", *v, 1, 100000);
    if (auto v = get(a, "quiet-zone")) ro.quiet_zone = static_cast<int>(to_integer("quiet-zone", *v, 0, 1000));
    umf::Field f = umf::load_field(path);
    // A screen's own field says which screen it belongs to, unless told otherwise.
    ro.caption = get(a, "caption").value_or(f.screen.empty() ? "" : "screen " + f.screen + ", field " + f.id);
    std::string bytes;
    try {
        bytes = umf::render_field(f, format, ro);
    } catch (const std::invalid_argument& e) {
        throw UsageError(e.what());
    }
    try {
        umf::write_file_atomically(*out, bytes);
    } catch (const umf::FileWriteError& e) {
        throw umf::FieldFileError(e.what());
    }
    std::printf("%s: %zu bytes\n", out->c_str(), bytes.size());
    return kOk;
}

int cmd_info(const Args& a) {
    std::string path = one_field_path(a, "info");
    umf::Field f = umf::load_field(path);
    auto report = umf::verify_field(f);
    auto contrast = umf::edge_contrast(f);
    double bound = umf::window_count_bound(f.window, f.colors, f.key);
    if (has_flag(a, "json")) {
        // nlohmann escapes what a field file may hold in its id and screen.
        nlohmann::ordered_json j{{"id", f.id}, {"width", f.width}, {"height", f.height}, {"window", f.window},
                                 {"colors", f.colors}, {"key", umf::to_string(f.key)}};
        if (!f.screen.empty()) j["screen"] = f.screen;
        j["windows"] = f.window_count();
        j["bound"] = static_cast<long long>(std::round(bound));
        j["fill"] = std::round(f.window_count() / bound * 1e4) / 1e4;
        j["orientable"] = report.orientable();
        j["conflicts"] = report.conflicts.size();
        j["flat_edges"] = std::round(contrast.flat_fraction() * 1e4) / 1e4;
        j["mean_step"] = std::round(contrast.mean_step * 1e4) / 1e4;
        std::printf("%s\n", j.dump(-1, ' ', false, nlohmann::ordered_json::error_handler_t::replace).c_str());
        return kOk;
    }
    std::printf("id          %s\n", f.id.c_str());
    if (!f.screen.empty()) std::printf("screen      %s\n", f.screen.c_str());
    std::printf("size        %d x %d modules\n", f.width, f.height);
    std::printf("window      %d x %d, key %s\n", f.window, f.window, umf::to_string(f.key));
    std::printf("colours     %d\n", f.colors);
    std::printf("windows     %ld of at most %.0f (%.1f %% of the counting bound)\n", f.window_count(), bound,
                100.0 * f.window_count() / bound);
    std::printf("edges       %.1f %% flat, mean step %.2f of full range\n", 100 * contrast.flat_fraction(),
                contrast.mean_step);
    std::printf("orientable  %s\n", report.orientable()
                                        ? "yes"
                                        : ("no, " + std::to_string(report.conflicts.size()) + " conflicts").c_str());
    return kOk;
}

}  // namespace

int main(int argc, char** argv) {
    if (argc < 2) {
        std::fputs(kUsageText, stderr);
        return kUsage;
    }
    std::string cmd = argv[1];
    try {
        if (cmd == "help" || cmd == "--help" || cmd == "-h") {
            std::fputs(kUsageText, stdout);
            return kOk;
        }
        if (cmd == "--version") {
            std::puts("umf-field 0.1.0");
            return kOk;
        }
        for (int i = 2; i < argc; ++i)
            if (std::strcmp(argv[i], "--help") == 0 || std::strcmp(argv[i], "-h") == 0) {
                std::fputs(kUsageText, stdout);
                return kOk;
            }
        if (cmd == "generate")
            return cmd_generate(parse_args(argc, argv, 2,
                                           {"width", "height", "window", "colors", "key", "seed", "chains", "threads",
                                            "time-limit", "contrast-steps", "id", "out"},
                                           {"quiet"}));
        if (cmd == "verify") return cmd_verify(parse_args(argc, argv, 2, {"max-listed"}, {}));
        if (cmd == "render")
            return cmd_render(
                parse_args(argc, argv, 2, {"out", "module-px", "module-mm", "dpi", "quiet-zone", "caption"}, {}));
        if (cmd == "info") return cmd_info(parse_args(argc, argv, 2, {}, {"json"}));
        throw UsageError("unknown command '" + cmd + "'");
    } catch (const UsageError& e) {
        std::fprintf(stderr, "umf-field: %s\n(umf-field --help lists the commands and options)\n", e.what());
        return kUsage;
    } catch (const umf::FieldFileError& e) {
        std::fprintf(stderr, "umf-field: %s\n", e.what());
        return kFileError;
    } catch (const std::invalid_argument& e) {
        std::fprintf(stderr, "umf-field: %s\n", e.what());
        return kUsage;
    } catch (const std::exception& e) {
        std::fprintf(stderr, "umf-field: error: %s\n", e.what());
        return kFileError;
    }
}
