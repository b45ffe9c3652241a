#include "tests/bench/metrics.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <iostream>
#include <numeric>
#include <set>
#include <sstream>

#include "tests/bench/frame_clock.hpp"

namespace umf::bench {
namespace {

double pct(int part, int whole) { return whole > 0 ? 100.0 * part / whole : kNaN; }

// Fixed-point text for tables; a dash where there is no number (nothing
// found, not measured) rather than "nan".
std::string num(double v, int decimals);

// The reason given for a false location at a success radius.
std::string wrong_place(double radius_modules) {
    return radius_modules == kSuccessRadiusModules ? std::string(kWrongPlace)
                                                   : "wrong place (found, error > " + num(radius_modules, 1) + " module)";
}

std::string num(double v, int decimals) {
    if (!std::isfinite(v)) return "–";
    char buf[64];
    std::snprintf(buf, sizeof buf, "%.*f", decimals, v);
    return buf;
}

nlohmann::json json_number(double v) { return std::isfinite(v) ? nlohmann::json(v) : nlohmann::json(nullptr); }

nlohmann::json to_json(const Summary& s) {
    nlohmann::json j;
    j["frames"] = s.frames;
    j["skipped"] = s.skipped;
    j["evaluated"] = s.evaluated;
    j["found"] = s.found;
    j["success"] = s.success;
    j["false_location"] = s.false_location;
    j["success_pct"] = json_number(s.success_pct);
    j["false_location_pct"] = json_number(s.false_pct);
    j["aim_error_modules"] = {{"median", json_number(s.err_median)}, {"p95", json_number(s.err_p95)}};
    if (!s.false_errors.empty()) j["false_location_errors_modules"] = s.false_errors;
    j["ms_per_frame"] = {{"median", json_number(s.ms_median)}, {"mean", json_number(s.ms_mean)}};
    j["pixels_visited_pct_median"] = json_number(s.pixels_median_pct);
    if (std::isfinite(s.stage_median_ms[0])) {
        nlohmann::json stages;
        for (std::size_t k = 0; k < kStageNames.size(); ++k) stages[kStageNames[k]] = json_number(s.stage_median_ms[k]);
        j["stage_ms_median"] = stages;
    }
    j["reasons"] = s.reasons;
    return j;
}

nlohmann::json to_json(const PulseSummary& p) {
    std::map<int, int> histogram;
    for (int g : p.gaps) ++histogram[g];
    nlohmann::json hist = nlohmann::json::object();
    for (const auto& [gap, count] : histogram) hist[std::to_string(gap)] = count;
    return {{"method", p.method},
            {"resolution", p.resolution},
            {"sequences", p.sequences},
            {"frames", p.frames},
            {"skipped", p.skipped},
            {"successes", p.successes},
            {"success_pct", json_number(p.success_pct)},
            {"false_locations", p.false_locations},
            {"false_location_pct", json_number(p.false_pct)},
            {"gaps", p.gaps.size()},
            {"gaps_le3_pct", json_number(p.gaps_le3_pct)},
            {"gaps_le5_pct", json_number(p.gaps_le5_pct)},
            {"gap_median", json_number(p.gap_median)},
            {"gap_max", p.gap_max},
            {"longest_miss", p.longest_miss},
            {"gap_histogram", hist},
            {"success_pct_by_screen", p.success_pct_by_screen},
            {"false_location_errors_modules", p.false_errors}};
}

// Opacity of table (a): 0.3, or the nearest one that was run.
double headline_opacity(const Report& r) {
    double best = kNaN;
    for (const auto& c : r.configs)
        if (!std::isfinite(best) || std::abs(c.opacity - 0.3) < std::abs(best - 0.3)) best = c.opacity;
    return best;
}

template <class T>
std::vector<T> unique_in_order(const std::vector<ConfigResult>& configs, T ConfigResult::*member) {
    std::vector<T> out;
    for (const auto& c : configs)
        if (std::find(out.begin(), out.end(), c.*member) == out.end()) out.push_back(c.*member);
    return out;
}

std::vector<std::string> pulse_resolutions(const std::vector<PulseSummary>& pulsing) {
    std::vector<std::string> out;
    for (const auto& p : pulsing)
        if (std::find(out.begin(), out.end(), p.resolution) == out.end()) out.push_back(p.resolution);
    return out;
}

const ConfigResult* find_config(const Report& r, const std::string& category, double opacity,
                                const std::string& resolution) {
    for (const auto& c : r.configs)
        if (c.category == category && std::abs(c.opacity - opacity) < 1e-9 && c.resolution == resolution) return &c;
    return nullptr;
}

const Summary* method(const ConfigResult* c, const std::string& name) {
    if (!c) return nullptr;
    auto it = c->methods.find(name);
    return it == c->methods.end() ? nullptr : &it->second;
}

bool has_method(const Report& r, const std::string& name) {
    return std::any_of(r.configs.begin(), r.configs.end(), [&](const ConfigResult& c) { return c.methods.count(name); });
}

// Reason counts per category, over every opacity and resolution.
std::map<std::string, std::pair<int, std::map<std::string, int>>> reasons_by_category(const Report& r,
                                                                                         const std::string& name) {
    std::map<std::string, std::pair<int, std::map<std::string, int>>> out;
    for (const auto& c : r.configs)
        if (const Summary* s = method(&c, name)) {
            auto& [evaluated, reasons] = out[c.category];
            evaluated += s->evaluated;
            for (const auto& [why, n] : s->reasons) reasons[why] += n;
        }
    return out;
}

void reasons_table(std::ostringstream& md, const Report& r, const std::string& name,
                   const std::vector<std::string>& categories) {
    const auto by_category = reasons_by_category(r, name);
    std::map<std::string, int> totals;
    for (const auto& [cat, entry] : by_category)
        for (const auto& [why, n] : entry.second) totals[why] += n;
    std::vector<std::string> columns;
    for (const auto& [why, n] : totals) columns.push_back(why);
    std::stable_sort(columns.begin(), columns.end(), [&](const auto& a, const auto& b) { return totals[a] > totals[b]; });
    if (columns.empty()) {
        md << "No failures.\n\n";
        return;
    }
    md << "| category | evaluated |";
    for (const auto& c : columns) md << " " << c << " |";
    md << "\n|---|---|";
    for (std::size_t i = 0; i < columns.size(); ++i) md << "---|";
    md << "\n";
    for (const auto& cat : categories) {
        auto it = by_category.find(cat);
        if (it == by_category.end()) continue;
        const auto& [evaluated, reasons] = it->second;
        md << "| " << cat << " | " << evaluated << " |";
        for (const auto& c : columns) {
            auto n = reasons.find(c);
            const int count = n == reasons.end() ? 0 : n->second;
            md << " " << count << " (" << num(pct(count, evaluated), 0) << " %) |";
        }
        md << "\n";
    }
    md << "\n";
}

// Section (c): the pulsing video's gaps between successes.
void write_pulsing(std::ostringstream& md, const Report& r, bool video) {
    const auto rule = [&](std::size_t columns) {
        md << "|";
        for (std::size_t i = 0; i < columns; ++i) md << "---|";
        md << "\n";
    };
    md << "## (c) Pulsing opacity: gaps between successful locations\n\n";
    if (r.pulsing.empty()) {
        md << "Not run.\n\n";
    } else {
        if (r.pulse_setup_md.empty())
            md << "25 fps, opacity 0.1..0.4 with a 1.5 s period, pitch swinging over about -20..+60 degrees, distance "
                  "100..400 mm, aim wandering around the screen centre; one video per screen content";
        else
            md << r.pulse_setup_md;
        if (video) md << " (umf video: one fresh tracker per video)";
        md << ". A gap is the number of frames from one success to the next (1 = consecutive frames); the longest "
              "miss also counts the frames before the first and after the last success of a video. Success % and "
              "false % are of all frames (frames with the centre off the screen count as misses).\n\n";
        md << "| method | resolution | frames | success % | false % | gaps | gaps <= 3 | gaps <= 5 | gap median | "
              "gap max | longest miss |";
        const std::vector<std::string> kinds = r.screen_kinds.empty()
                                                   ? std::vector<std::string>{"document", "code_dark", "web_page", "photo", "blank"}
                                                   : r.screen_kinds;
        for (const auto& kind : kinds) md << " " << kind << " |";
        md << "\n";
        rule(11 + kinds.size());
        // Rows grouped by resolution, methods in report order.
        std::vector<const PulseSummary*> rows;
        for (const auto& res : pulse_resolutions(r.pulsing))
            for (const auto& m : kMethods)
                for (const auto& p : r.pulsing)
                    if (p.resolution == res && p.method == m.key) rows.push_back(&p);
        for (const auto& p : r.pulsing)
            if (std::find(rows.begin(), rows.end(), &p) == rows.end()) rows.push_back(&p);
        for (const PulseSummary* p : rows) {
            md << "| " << method_label(p->method) << " | " << p->resolution << " | " << p->frames << " | "
               << num(p->success_pct, 1) << " | " << num(p->false_pct, 1) << " | " << p->gaps.size() << " | "
               << num(p->gaps_le3_pct, 1) << " % | " << num(p->gaps_le5_pct, 1) << " % | " << num(p->gap_median, 0)
               << " | " << p->gap_max << " | " << p->longest_miss << " |";
            for (const auto& kind : kinds) {
                auto it = p->success_pct_by_screen.find(kind);
                md << " " << (it == p->success_pct_by_screen.end() ? "–" : num(it->second, 0)) << " |";
            }
            md << "\n";
        }
        md << "\nThe last " << kinds.size() << " columns: success % per screen content.\n\n";
    }
}

}  // namespace

std::string method_label(const std::string& key) {
    for (const auto& m : kMethods)
        if (key == m.key) return m.label;
    return key;
}

double percentile(std::vector<double> values, double p) {
    values.erase(std::remove_if(values.begin(), values.end(), [](double v) { return !std::isfinite(v); }),
                 values.end());
    if (values.empty()) return kNaN;
    std::sort(values.begin(), values.end());
    const double at = std::clamp(p, 0.0, 100.0) / 100 * static_cast<double>(values.size() - 1);
    const auto lo = static_cast<std::size_t>(std::floor(at));
    const std::size_t hi = std::min(lo + 1, values.size() - 1);
    return values[lo] + (at - static_cast<double>(lo)) * (values[hi] - values[lo]);
}

int module_px_bin(double module_px) {
    int bin = 0;
    while (bin + 2 < static_cast<int>(kModulePxBins.size()) &&
           module_px >= kModulePxBins[static_cast<std::size_t>(bin) + 1])
        ++bin;
    return bin;
}

std::string module_px_bin_label(int bin) {
    const auto lo = kModulePxBins[static_cast<std::size_t>(bin)], hi = kModulePxBins[static_cast<std::size_t>(bin) + 1];
    if (bin == 0) return "< " + num(hi, 0);
    if (bin + 2 == static_cast<int>(kModulePxBins.size())) return ">= " + num(lo, 0);
    return num(lo, 0) + "–" + num(hi, 0);
}

void tally(Report& report, const std::string& method, double opacity, double module_px, const std::string& screen,
           const Outcome& outcome) {
    if (outcome.skipped) return;
    for (Tally* t : {&report.by_module_px[method][opacity][module_px_bin(module_px)],
                     &report.by_screen[method][opacity][screen]}) {
        ++t->evaluated;
        t->success += outcome.success();
        t->false_location += outcome.false_location();
    }
}

Summary summarise(const std::vector<Outcome>& outcomes) {
    Summary s;
    s.frames = static_cast<int>(outcomes.size());
    std::vector<double> errors, ms, pixels;
    std::array<std::vector<double>, kStageNames.size()> stages;
    for (const auto& o : outcomes) {
        if (o.skipped) {
            ++s.skipped;
            continue;
        }
        ++s.evaluated;
        if (std::isfinite(o.ms)) ms.push_back(o.ms);  // a dropped frame (frame_clock.hpp) made no call
        pixels.push_back(o.pixels_pct);
        for (std::size_t k = 0; k < stages.size(); ++k) stages[k].push_back(o.stage_ms[k]);
        if (o.found) {
            ++s.found;
            errors.push_back(o.error_modules);
        }
        if (o.success()) ++s.success;
        if (o.false_location()) {
            ++s.false_location;
            s.false_errors.push_back(o.error_modules);
            ++s.reasons[wrong_place(o.radius_modules)];
        }
        if (!o.found) ++s.reasons[o.failure.empty() ? "(no reason given)" : o.failure];
    }
    s.success_pct = pct(s.success, s.evaluated);
    s.false_pct = pct(s.false_location, s.evaluated);
    s.err_median = percentile(errors, 50);
    s.err_p95 = percentile(errors, 95);
    s.ms_median = percentile(ms, 50);
    s.ms_mean = ms.empty() ? kNaN : std::accumulate(ms.begin(), ms.end(), 0.0) / static_cast<double>(ms.size());
    s.pixels_median_pct = percentile(pixels, 50);
    for (std::size_t k = 0; k < stages.size(); ++k) s.stage_median_ms[k] = percentile(stages[k], 50);
    return s;
}

PulseSummary summarise_pulse(const std::string& method, const std::string& resolution,
                             const std::vector<std::string>& screens,
                             const std::vector<std::vector<Outcome>>& outcomes) {
    PulseSummary p;
    p.method = method;
    p.resolution = resolution;
    p.sequences = static_cast<int>(outcomes.size());
    for (std::size_t s = 0; s < outcomes.size(); ++s) {
        const auto& seq = outcomes[s];
        int last = -1, hits = 0;
        for (int i = 0; i < static_cast<int>(seq.size()); ++i) {
            const Outcome& o = seq[static_cast<std::size_t>(i)];
            p.skipped += o.skipped;
            if (!o.skipped && o.false_location()) {
                ++p.false_locations;
                p.false_errors.push_back(o.error_modules);
            }
            if (o.skipped || !o.success()) continue;
            ++hits;
            if (last >= 0) p.gaps.push_back(i - last);
            p.longest_miss = std::max(p.longest_miss, i - last - 1);
            last = i;
        }
        p.longest_miss = std::max(p.longest_miss, static_cast<int>(seq.size()) - last - 1);
        p.frames += static_cast<int>(seq.size());
        p.successes += hits;
        if (s < screens.size()) p.success_pct_by_screen[screens[s]] = pct(hits, static_cast<int>(seq.size()));
    }
    p.success_pct = pct(p.successes, p.frames);
    p.false_pct = pct(p.false_locations, p.frames);
    const auto share = [&](int limit) {
        const auto n = std::count_if(p.gaps.begin(), p.gaps.end(), [&](int g) { return g <= limit; });
        return pct(static_cast<int>(n), static_cast<int>(p.gaps.size()));
    };
    p.gaps_le3_pct = share(3);
    p.gaps_le5_pct = share(5);
    p.gap_median = percentile(std::vector<double>(p.gaps.begin(), p.gaps.end()), 50);
    p.gap_max = p.gaps.empty() ? 0 : *std::max_element(p.gaps.begin(), p.gaps.end());
    return p;
}

void PulseRun::add(const std::string& kind, std::vector<Outcome> umf, std::vector<Outcome> video,
                   std::vector<Outcome> aruco, double minutes) {
    const auto hits = [](const std::vector<Outcome>& out) {
        return std::to_string(std::count_if(out.begin(), out.end(), [](const Outcome& o) { return o.success(); })) + "/" +
               std::to_string(out.size());
    };
    std::cerr << "[pulsing " << resolution_ << " " << kind << "] umf " << hits(umf);
    if (video_) std::cerr << ", umf video " << hits(video);
    if (aruco_) std::cerr << ", ArUco " << hits(aruco);
    std::cerr << ", elapsed " << minutes << " min\n";
    kinds_.push_back(kind);
    umf_.push_back(std::move(umf));
    video_out_.push_back(std::move(video));
    aruco_out_.push_back(std::move(aruco));
}

void PulseRun::summarise_into(Report& report) const {
    report.pulsing.push_back(summarise_pulse("umf", resolution_, kinds_, umf_));
    if (video_) report.pulsing.push_back(summarise_pulse("umf_video", resolution_, kinds_, video_out_));
    if (aruco_) report.pulsing.push_back(summarise_pulse("aruco", resolution_, kinds_, aruco_out_));
}

nlohmann::json to_json(const Report& r) {
    nlohmann::json j;
    j["command"] = r.command;
    j["started"] = r.started;
    j["wall_time_s"] = r.wall_s;
    j["settings"] = r.settings;
    j["success_radius_modules"] = r.success_radius_modules;
    nlohmann::json configs = nlohmann::json::array();
    for (const auto& c : r.configs) {
        nlohmann::json e = {{"category", c.category}, {"opacity", c.opacity}, {"resolution", c.resolution}};
        e["module_px_in_image"] = {{"min", json_number(c.module_px[0])},
                                   {"median", json_number(c.module_px[1])},
                                   {"max", json_number(c.module_px[2])}};
        // Both methods see the same frames, so any method's counts do.
        if (!c.methods.empty()) {
            e["frames"] = c.methods.begin()->second.frames;
            e["skipped"] = c.methods.begin()->second.skipped;
        }
        for (const auto& [name, s] : c.methods) e["methods"][name] = to_json(s);
        configs.push_back(e);
    }
    j["configurations"] = configs;
    nlohmann::json reasons = nlohmann::json::object();
    for (const auto& m : kMethods)
        for (const auto& [cat, entry] : reasons_by_category(r, m.key))
            reasons[cat][m.key] = {{"evaluated", entry.first}, {"reasons", entry.second}};
    j["failure_reasons_by_category"] = reasons;
    nlohmann::json pulsing = nlohmann::json::array();
    for (const auto& p : r.pulsing) pulsing.push_back(to_json(p));
    j["pulsing"] = pulsing;
    nlohmann::json timing = nlohmann::json::object();
    for (const auto& [name, by_res] : r.all_ms)
        for (const auto& [res, ms] : by_res)
            timing[name][res] = {{"frames", ms.size()},
                                 {"median", json_number(percentile(ms, 50))},
                                 {"mean", json_number(ms.empty() ? kNaN
                                                                 : std::accumulate(ms.begin(), ms.end(), 0.0) /
                                                                       static_cast<double>(ms.size()))},
                                 {"p95", json_number(percentile(ms, 95))}};
    j["ms_per_frame_by_resolution"] = timing;
    const auto tally_json = [](const Tally& t) {
        return nlohmann::json{{"evaluated", t.evaluated},
                              {"success", t.success},
                              {"false_location", t.false_location},
                              {"success_pct", json_number(pct(t.success, t.evaluated))},
                              {"false_location_pct", json_number(pct(t.false_location, t.evaluated))}};
    };
    nlohmann::json by_px = nlohmann::json::object(), by_screen = nlohmann::json::object();
    for (const auto& [name, by_op] : r.by_module_px)
        for (const auto& [op, bins] : by_op)
            for (const auto& [bin, t] : bins) by_px[name][num(op, 2)][module_px_bin_label(bin)] = tally_json(t);
    for (const auto& [name, by_op] : r.by_screen)
        for (const auto& [op, kinds] : by_op)
            for (const auto& [kind, t] : kinds) by_screen[name][num(op, 2)][kind] = tally_json(t);
    const std::string pooled =
        r.pooled_over.empty() ? "near_far, horizontal, rotation, perspective, general; all resolutions" : r.pooled_over;
    j["success_by_module_px"] = {{"pooled_over", pooled},
                                 {"by_method_and_opacity", by_px}};
    j["success_by_screen"] = {{"pooled_over", pooled},
                              {"by_method_and_opacity", by_screen}};
    return j;
}

std::string to_markdown(const Report& r) {
    std::ostringstream md;
    const auto categories = unique_in_order(r.configs, &ConfigResult::category);
    const auto resolutions = unique_in_order(r.configs, &ConfigResult::resolution);
    auto opacities = unique_in_order(r.configs, &ConfigResult::opacity);
    std::sort(opacities.begin(), opacities.end());
    const bool aruco = has_method(r, "aruco");
    const bool video = has_method(r, "umf_video");
    const double op = headline_opacity(r);
    // The methods that were run, in report order.
    std::vector<MethodName> run;
    for (const auto& m : kMethods)
        if (has_method(r, m.key)) run.push_back(m);
    const auto rule = [&](std::size_t columns) {
        md << "|";
        for (std::size_t i = 0; i < columns; ++i) md << "---|";
        md << "\n";
    };

    md << "# " << (r.title.empty() ? "Detector benchmark: umf against ArUco on simulated phone photos" : r.title) << "\n\n";
    md << "Command: `" << r.command << "`, started " << r.started << ", wall time " << num(r.wall_s / 60, 1)
       << " min. Written by `tests/bench/umf_benchmark.cpp`; every number below is also in `" << r.json_name << "`.";
    if (r.settings.contains("load_average_at_start") && r.settings.contains("load_average_at_end"))
        md << " Load average (1, 5, 15 min) at the start " << r.settings["load_average_at_start"].get<std::string>()
           << ", at the end " << r.settings["load_average_at_end"].get<std::string>()
           << " on " << r.settings.value("hardware_threads", 0) << " hardware threads: other work on the machine "
           << "inflates the times.";
    md << "\n\n";
    if (!r.setup_md.empty()) {
        md << r.setup_md << "\n\n";
    } else {
    md << "Setup: a 1920 x 1080 screen, 527 mm wide, showing one of five contents (document, code_dark, web_page, "
          "photo, blank; frame i shows kind i mod 5). umf: the field `" << r.settings.value("field", std::string("?")) << "` (30 px modules, covering the whole "
          "screen) blended in at the given opacity. ArUco: an 8 x 4 board of DICT_4X4_250 markers (180 px = 6 cells "
          "of 30 px, 60 px gaps, white background over the whole screen) blended in the same way; located by "
          "`cv::aruco::detectMarkers` (default parameters) and a homography from the markers' corners. All methods "
          "see the very same poses, contents, degradations and occluders. A phone camera (65 degree horizontal field "
          "of view) at 200..600 mm films at 25 fps; every frame has defocus (sigma 0.5..1.5 px), noise (sigma 2..3), "
          "JPEG 80, and some frames motion blur (1..4 px, 30 %), RGB subpixel stripes (moire, 15 %) or a lamp's "
          "glare (10 %). occlusion: general motion plus a hand or mug over 15..35 % of the frame (never the centre); "
          "low_light: general motion at exposure 0.35, gamma 1.2, noise sigma 6.\n\n";
    }
    md << "Methods: **umf** is the detector on each frame on its own (`umf::Detector::detect`, single frame). "
          "**umf video** is the tracker (`umf::Tracker`, on the same detector) fed a configuration's frames in their "
          "order, the consecutive frames of the category's "
       << r.settings.value("fps", 25) << " fps camera motion, as a phone feeds its camera frames "
          "(one fresh tracker per configuration and per pulsing video): it predicts the field's next place from the "
          "last two, confirms it there on the field's own edges (`Detector::follow`), and falls back to a full "
          "detection (with the last place as a prior) when that fails. It counts as found when the tracker is "
          "locked, its aim point is the tracker's (smoothed) one, its time is the whole `update()` call. Frames "
          "whose centre is off the screen are still fed to the tracker but left out of its statistics. **ArUco** is "
          "the single-frame baseline above.\n\n";
    if (const auto tracker = r.settings.find("umf_video_tracker"); tracker != r.settings.end()) {
        if (tracker->value("spread_search", false)) {
            md << "umf video's tracker spreads its search over the frames without a lock";
            if (const double share = tracker->value("frame_share", 0.0); share > 0) {
                md << ", each frame held to " << num(share, 2)
                   << " of the device's time between two frames (the round's steps taken up where the last frame "
                      "stopped)";
                if (tracker->value("hold_first_scan", false))
                    md << ", its first scan after the part around the aim to "
                       << num(share * tracker->value("first_scan_times", 1.0), 2) << " of it";
                else
                    md << ", its first scan whole on every frame";
                md << ".\n\n";
            } else {
                md << " (search budget " << num(tracker->value("search_budget_ms", 0.0), 1) << ").\n\n";
            }
        }
        if (const double slowdown = tracker->value("realtime_slowdown", 0.0); slowdown > 0)
            md << "umf video in real time: a device " << num(slowdown, 1)
               << " times slower than this machine; the frames arrive at the video's rate and one that arrives while "
                  "the tracker is still on an earlier frame is dropped (not found, \"" << kDroppedFrame
               << "\"; left out of the times).\n\n";
    }
    if (r.success_radius_modules == kSuccessRadiusModules)
        md << "Success: located within " << num(kSuccessRadiusModules, 0) << " module (30 screen px)";
    else
        md << "Success: located within " << num(r.success_radius_modules, 1) << " module";
    md << " of the true screen point under the image centre; false: located farther away. "
          "Percentages are of the evaluated frames (frames whose centre falls off the screen are skipped for all "
          "methods; the skipped count is in the JSON). Errors are in modules over the located frames; ms per frame "
          "is the median of one detector call (for umf video one tracker update) on one thread (OpenCV limited to "
          "one thread); px % is the median share of the image's pixels the umf detector read; module px is the "
          "range of image pixels per module at the image centre.\n\n";

    if (r.configs.empty()) {  // a run of the pulsing video alone
        write_pulsing(md, r, video);
        return md.str();
    }

    md << "## (a) Per category at opacity " << num(op, 2) << "\n\n";
    md << "Per resolution two tables: success, false locations and time of every method side by side, then the "
          "aim errors of the located frames and the umf pixels read.\n\n";
    for (const auto& res : resolutions) {
        md << "### " << res << "\n\n";
        md << "| category | frames (skipped) | module px |";
        for (const char* what : {"ok %", "false %", "ms"})
            for (const auto& m : run) md << " " << m.label << " " << what << " |";
        md << "\n";
        rule(3 + 3 * run.size());
        for (const auto& cat : categories) {
            const ConfigResult* c = find_config(r, cat, op, res);
            const Summary* u = c && !c->methods.empty() ? &c->methods.begin()->second : nullptr;
            if (!u) continue;
            md << "| " << cat << " | " << u->frames << " (" << u->skipped << ") | " << num(c->module_px[0], 0) << "–"
               << num(c->module_px[2], 0) << " |";
            for (const auto& m : run) {
                const Summary* s = method(c, m.key);
                md << " " << (s ? num(s->success_pct, 1) : "–") << " |";
            }
            for (const auto& m : run) {
                const Summary* s = method(c, m.key);
                md << " " << (s ? num(s->false_pct, 1) : "–") << " |";
            }
            for (const auto& m : run) {
                const Summary* s = method(c, m.key);
                md << " " << (s ? num(s->ms_median, 1) : "–") << " |";
            }
            md << "\n";
        }
        md << "\n| category |";
        std::size_t columns = 1;
        for (const auto& m : run) {
            md << " " << m.label << " err med | " << m.label << " err p95 |";
            columns += 2;
        }
        for (const auto& m : run)
            if (m.key != std::string("aruco")) {
                md << " " << m.label << " px % |";
                ++columns;
            }
        md << "\n";
        rule(columns);
        for (const auto& cat : categories) {
            const ConfigResult* c = find_config(r, cat, op, res);
            if (!c || c->methods.empty()) continue;
            md << "| " << cat << " |";
            for (const auto& m : run) {
                const Summary* s = method(c, m.key);
                md << " " << (s ? num(s->err_median, 2) : "–") << " | " << (s ? num(s->err_p95, 2) : "–") << " |";
            }
            for (const auto& m : run)
                if (m.key != std::string("aruco")) {
                    const Summary* s = method(c, m.key);
                    md << " " << (s ? num(s->pixels_median_pct, 1) : "–") << " |";
                }
            md << "\n";
        }
        md << "\n";
    }

    const std::string sweep = std::find(categories.begin(), categories.end(), "general") != categories.end()
                                  ? "general"
                                  : (categories.empty() ? "" : categories.front());
    const auto by_opacity = [&](double Summary::*value) {
        md << "| opacity |";
        for (const auto& res : resolutions)
            for (const auto& m : run) md << " " << m.label << " " << res << " |";
        md << "\n";
        rule(1 + resolutions.size() * run.size());
        for (double o : opacities) {
            md << "| " << num(o, 2) << " |";
            for (const auto& res : resolutions) {
                const ConfigResult* c = find_config(r, sweep, o, res);
                for (const auto& m : run) {
                    const Summary* s = method(c, m.key);
                    md << " " << (s ? num(s->*value, 1) : "–") << " |";
                }
            }
            md << "\n";
        }
    };
    md << "## (b) Success % against opacity, " << sweep << " category\n\n";
    by_opacity(&Summary::success_pct);
    md << "\nFalse locations in the same runs (%):\n\n";
    by_opacity(&Summary::false_pct);
    md << "\n";

    write_pulsing(md, r, video);

    const std::string stage_res = std::find(resolutions.begin(), resolutions.end(), "640x480") != resolutions.end()
                                      ? "640x480"
                                      : (resolutions.empty() ? "" : resolutions.front());
    md << "## (d) umf stage times, " << stage_res << ", opacity " << num(op, 2)
       << " (median ms per frame over the evaluated frames)\n\n";
    md << "Single frame (`Detector::detect`):\n\n| category |";
    for (const char* stage : kStageNames) md << " " << stage << " |";
    md << " total |\n";
    rule(kStageNames.size() + 2);
    for (const auto& cat : categories)
        if (const Summary* u = method(find_config(r, cat, op, stage_res), "umf")) {
            md << "| " << cat << " |";
            for (double v : u->stage_median_ms) md << " " << num(v, 2) << " |";
            md << " " << num(u->ms_median, 2) << " |\n";
        }
    md << "\nMedians of each stage separately, so they need not add up to the total. A stage that did not run (the "
          "search ended before it) counts as 0 ms. refine: the fit of the place to the field's own module edges "
          "after the vote.\n\n";

    md << "## Time per frame over all categories and opacities\n\n| method | resolution | frames | median ms | "
          "mean ms | p95 ms |\n";
    rule(6);
    for (const auto& m : kMethods) {
        const auto by_res = r.all_ms.find(m.key);
        if (by_res == r.all_ms.end()) continue;
        for (const auto& res : resolutions) {
            auto it = by_res->second.find(res);
            if (it == by_res->second.end()) continue;
            const auto& ms = it->second;
            const double mean =
                ms.empty() ? kNaN : std::accumulate(ms.begin(), ms.end(), 0.0) / static_cast<double>(ms.size());
            md << "| " << m.label << " | " << res << " | " << ms.size() << " | " << num(percentile(ms, 50), 1) << " | "
               << num(mean, 1) << " | " << num(percentile(ms, 95), 1) << " |\n";
        }
    }
    md << "\n";

    md << "## (e) Why frames were not successes, per category (all opacities and resolutions)\n\n";
    md << "umf: `Detection::failure` of the frames not found, and \"" << wrong_place(r.success_radius_modules)
       << "\"; share of the evaluated frames.\n\n";
    reasons_table(md, r, "umf", categories);
    if (video) {
        md << "umf video: for the frames where the tracker is not locked, the failure of that frame's detection (the "
              "full detection after a failed follow), or the tracker's state (lost, searching) when it gives none; "
              "and \""
           << wrong_place(r.success_radius_modules) << "\".\n\n";
        reasons_table(md, r, "umf_video", categories);
    }
    if (aruco) {
        md << "ArUco:\n\n";
        reasons_table(md, r, "aruco", categories);
    }
    if (!r.by_module_px.empty()) {
        const auto row = [&](const std::string& label, const auto& lookup) {
            md << "| " << label << " |";
            bool first = true;
            for (const auto& m : run) {
                const Tally t = lookup(m.key);
                if (first) md << " " << t.evaluated << " |";
                first = false;
                md << " " << num(pct(t.success, t.evaluated), 1) << " | " << num(pct(t.false_location, t.evaluated), 1)
                   << " |";
            }
            md << "\n";
        };
        std::ostringstream head_text;
        head_text << " frames |";
        for (const auto& m : run) head_text << " " << m.label << " ok % | " << m.label << " false % |";
        head_text << "\n|";
        for (std::size_t i = 0; i < 2 + 2 * run.size(); ++i) head_text << "---|";
        head_text << "\n";
        const std::string head = head_text.str();
        md << "## (f) Success by module size in the image, opacity " << num(op, 2)
           << "\n\n"
           << (r.pooled_over.empty() ? "Pooled over the five motion categories (near_far, horizontal, rotation, "
                                       "perspective, general) and all resolutions; module px = image pixels per 30 px "
                                       "module (ArUco cell) at the image centre."
                                     : r.pooled_over)
           << "\n\n| module px |" << head;
        for (int bin = 0; bin + 1 < static_cast<int>(kModulePxBins.size()); ++bin)
            row(module_px_bin_label(bin), [&](const std::string& name) {
                const auto m = r.by_module_px.find(name);
                if (m == r.by_module_px.end()) return Tally{};
                const auto o = m->second.find(op);
                if (o == m->second.end()) return Tally{};
                const auto b = o->second.find(bin);
                return b == o->second.end() ? Tally{} : b->second;
            });
        md << "\n## (g) Success by screen content, opacity " << num(op, 2) << "\n\nPooled as in (f).\n\n| screen |" << head;
        std::vector<std::string> kinds = r.screen_kinds;
        if (kinds.empty()) kinds = {"document", "code_dark", "web_page", "photo", "blank"};
        for (const std::string& kind : kinds)
            row(kind, [&](const std::string& name) {
                const auto m = r.by_screen.find(name);
                if (m == r.by_screen.end()) return Tally{};
                const auto o = m->second.find(op);
                if (o == m->second.end()) return Tally{};
                const auto k = o->second.find(kind);
                return k == o->second.end() ? Tally{} : k->second;
            });
        md << "\n";
    }

    return md.str();
}

}  // namespace umf::bench
