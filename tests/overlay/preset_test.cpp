#include "shared/overlay/preset.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>

#include "shared/overlay/pulse.hpp"
#include "tests/support/replaced.hpp"

using namespace umf::overlay;

namespace {

using umf::test::replaced;

const Preset& built_in(const std::string& name) {
    static const auto presets = built_in_presets();
    const Preset* p = find_preset(presets, name);
    if (!p) throw std::runtime_error("no built-in preset " + name);
    return *p;
}

// A preset with every member set, none at its default.
Preset full_preset() {
    Preset p;
    p.name = "custom";
    p.opacity_min = 0.05;
    p.opacity_max = 0.35;
    p.period_s = 2.5;
    p.waveform = Waveform::triangle;
    p.module_px = 24;
    p.palette = {"#102030", "#F0E0D0"};
    p.blur = 0.5;
    p.region = Region::focus;
    p.focus_radius_modules = 12;
    p.activation = Activation::always;
    p.fade_s = 0;
    return p;
}

void expect_error(const std::string& text, const std::string& words) {
    try {
        parse_preset(text, "case.json");
        ADD_FAILURE() << "accepted: " << text;
    } catch (const PresetError& e) {
        std::string msg = e.what();
        EXPECT_NE(msg.find(words), std::string::npos) << "message: " << msg << "\nexpected words: " << words;
        EXPECT_EQ(msg.rfind("case.json", 0), 0u) << msg;
    }
}

TEST(OverlayPreset, BuiltInsAreValidAndAsSpecified) {
    auto presets = built_in_presets();
    ASSERT_EQ(presets.size(), 6u);
    for (const auto& p : presets) EXPECT_EQ(describe_invalid(p), "") << p.name;

    const Preset& subtle = built_in("subtle");
    EXPECT_EQ(subtle.opacity_min, 0.08);
    EXPECT_EQ(subtle.opacity_max, 0.25);
    EXPECT_EQ(subtle.period_s, 1.5);
    EXPECT_EQ(subtle.waveform, Waveform::sine);
    EXPECT_EQ(subtle.activation, Activation::on_demand);
    EXPECT_EQ(subtle.region, Region::full);
    const Preset& balanced = built_in("balanced");
    EXPECT_EQ(balanced.opacity_min, 0.1);
    EXPECT_EQ(balanced.opacity_max, 0.4);
    EXPECT_EQ(balanced.activation, Activation::on_demand);
    const Preset& visible = built_in("visible");
    EXPECT_EQ(visible.opacity_min, 0.3);
    EXPECT_EQ(visible.opacity_max, 0.5);
    EXPECT_EQ(visible.period_s, 2.0);
    EXPECT_EQ(visible.activation, Activation::always);
    const Preset& still = built_in("static");
    EXPECT_EQ(still.period_s, 0.0);
    EXPECT_EQ(still.opacity_max, 0.3);
    EXPECT_EQ(still.activation, Activation::always);
    const Preset& kiosk = built_in("kiosk");
    EXPECT_EQ(kiosk.module_px, 40.0);
    EXPECT_EQ(kiosk.opacity_min, 0.15);
    EXPECT_EQ(kiosk.activation, Activation::always);
    const Preset& invisible = built_in("invisible");
    EXPECT_EQ(invisible.opacity_min, 0.01);
    EXPECT_EQ(invisible.opacity_max, 0.04);
    EXPECT_EQ(invisible.period_s, 1.5);
    EXPECT_EQ(invisible.waveform, Waveform::sine);
    EXPECT_EQ(invisible.activation, Activation::on_demand);
    EXPECT_EQ(find_preset(presets, "nonesuch"), nullptr);
}

TEST(OverlayPreset, RoundTripsThroughJson) {
    auto presets = built_in_presets();
    presets.push_back(full_preset());
    for (const auto& p : presets) EXPECT_EQ(parse_preset(preset_to_json(p)), p) << p.name;
    EXPECT_EQ(parse_presets(presets_to_json(presets)), presets);

    auto path = std::filesystem::temp_directory_path() / "umf_presets_test.json";
    save_presets(presets, path.string());
    EXPECT_EQ(load_presets(path.string()), presets);
    EXPECT_FALSE(std::filesystem::exists(path.string() + ".tmp"));
    std::filesystem::remove(path);
}

TEST(OverlayPreset, LeftOutMembersTakeTheDefaults) {
    Preset p = parse_preset(R"({"name": "mine", "opacity_max": 0.6})");
    Preset expected;
    expected.name = "mine";
    expected.opacity_max = 0.6;
    EXPECT_EQ(p, expected);
    EXPECT_EQ(parse_presets("[]").size(), 0u);
}

TEST(OverlayPreset, RejectsEveryInvalidMemberNamingIt) {
    const std::string g = preset_to_json(full_preset());
    expect_error("", "not valid JSON");
    expect_error("[]", "a preset must be a JSON object");
    expect_error(replaced(g, R"("name": "custom",)", ""), "missing \"name\"");
    expect_error(replaced(g, R"("custom")", "7"), "\"name\" must be a string");
    expect_error(replaced(g, R"("custom")", "\"\""), "\"name\" must not be empty");
    expect_error(replaced(g, R"("custom")", "\"" + std::string(65, 'n') + "\""), "\"name\" must be at most 64 bytes");
    expect_error(replaced(g, "\"opacity_min\": 0.05", "\"opacity_min\": -0.1"), "\"opacity_min\" must be 0..1, not -0.1");
    expect_error(replaced(g, "\"opacity_max\": 0.35", "\"opacity_max\": 1.5"), "\"opacity_max\" must be 0..1, not 1.5");
    expect_error(replaced(g, "\"opacity_max\": 0.35", "\"opacity_max\": 0.01"),
                 "(\"custom\"): \"opacity_min\" 0.05 is above \"opacity_max\" 0.01");
    expect_error(replaced(g, "\"opacity_min\": 0.05", "\"opacity_min\": \"low\""), "\"opacity_min\" must be a number");
    expect_error(replaced(g, "\"period_s\": 2.5", "\"period_s\": 0.2"), "\"period_s\" must be 0.5..60, not 0.2 (0 for a static field)");
    expect_error(replaced(g, "\"period_s\": 2.5", "\"period_s\": 61"), "\"period_s\" must be 0.5..60");
    expect_error(replaced(g, "\"period_s\": 2.5", "\"period_s\": -1"), "\"period_s\"");
    expect_error(replaced(g, "\"triangle\"", "\"square\""), "\"waveform\" is \"square\", expected \"sine\" or \"triangle\"");
    expect_error(replaced(g, "\"triangle\"", "1"), "\"waveform\" must be one of");
    expect_error(replaced(g, "\"module_px\": 24.0", "\"module_px\": 2"), "\"module_px\" must be 4..256, not 2");
    expect_error(replaced(g, "\"module_px\": 24.0", "\"module_px\": 300"), "\"module_px\" must be 4..256, not 300");
    expect_error(replaced(g, "\"#F0E0D0\"", "\"red\""), "\"palette\" entry 'red' is not a #rrggbb colour");
    expect_error(replaced(g, ",\n    \"#F0E0D0\"", ""), "\"palette\" must be empty (the field's own) or have 2 to 10 colours, not 1");
    expect_error(replaced(g, "\"#F0E0D0\"", "3"), "\"palette\" must be an array of \"#rrggbb\" strings");
    expect_error(replaced(g, "\"blur\": 0.5", "\"blur\": 2"), "\"blur\" must be 0..1, not 2");
    expect_error(replaced(g, "\"focus\"", "\"half\""), "\"region\" is \"half\", expected \"full\" or \"focus\"");
    expect_error(replaced(g, "\"focus_radius_modules\": 12.0", "\"focus_radius_modules\": 0"),
                 "\"focus_radius_modules\" must be 1..1000, not 0");
    expect_error(replaced(g, "\"always\"", "\"sometimes\""), "\"activation\" is \"sometimes\", expected \"always\" or \"on_demand\"");
    expect_error(replaced(g, "\"fade_s\": 0.0", "\"fade_s\": -1"), "\"fade_s\" must be 0..600, not -1");
    expect_error(replaced(g, "\"blur\"", "\"blurr\""), "unknown member \"blurr\"");
}

TEST(OverlayPreset, RejectsBadPresetFiles) {
    auto expect_file_error = [](const std::string& text, const std::string& words) {
        try {
            parse_presets(text, "presets.json");
            ADD_FAILURE() << "accepted: " << text;
        } catch (const PresetError& e) {
            EXPECT_NE(std::string(e.what()).find(words), std::string::npos) << e.what();
        }
    };
    expect_file_error("{\"name\": \"a\"}", "presets.json: the top level must be a JSON array of presets");
    expect_file_error("[{\"name\": \"a\"}, {\"name\": \"b\", \"blur\": 9}]", "presets.json: preset 1 (\"b\"): \"blur\"");
    expect_file_error("[{\"name\": \"a\"}, {\"name\": \"a\"}]", "presets.json: preset 1: name \"a\" is used twice");
    expect_file_error(std::string(kMaxPresetFileBytes + 1, ' '), "more than the limit");
    EXPECT_THROW(load_presets("/nonexistent/presets.json"), PresetError);
    EXPECT_THROW(presets_to_json({full_preset(), full_preset()}), std::invalid_argument);
    Preset bad = full_preset();
    bad.blur = std::nan("");
    EXPECT_NE(describe_invalid(bad).find("\"blur\""), std::string::npos);
    EXPECT_THROW(preset_to_json(bad), std::invalid_argument);
    bad = full_preset();
    bad.name = "bad \xff";
    EXPECT_EQ(describe_invalid(bad), "\"name\" is not valid UTF-8");
}

TEST(OverlayPulse, SineRisesFromMinToMaxAndBack) {
    Preset p = built_in("balanced");  // 0.1..0.4, 1.5 s
    const double T = p.period_s;
    EXPECT_NEAR(opacity_at(p, 0), 0.1, 1e-12);
    EXPECT_NEAR(opacity_at(p, T / 4), 0.25, 1e-12);
    EXPECT_NEAR(opacity_at(p, T / 2), 0.4, 1e-12);
    EXPECT_NEAR(opacity_at(p, 3 * T / 4), 0.25, 1e-12);
    EXPECT_NEAR(opacity_at(p, T), 0.1, 1e-12);
    EXPECT_NEAR(opacity_at(p, 7 * T + T / 2), 0.4, 1e-9);
    EXPECT_NEAR(opacity_at(p, -T / 4), 0.25, 1e-12);
    // The curve itself, not just its landmarks.
    EXPECT_NEAR(opacity_at(p, T / 8), 0.1 + 0.3 * (1 - std::cos(std::acos(-1.0) / 4)) / 2, 1e-12);
}

TEST(OverlayPulse, TriangleIsLinearUpAndDown) {
    Preset p = full_preset();  // 0.05..0.35, 2.5 s, triangle
    const double T = p.period_s;
    EXPECT_NEAR(opacity_at(p, 0), 0.05, 1e-12);
    EXPECT_NEAR(opacity_at(p, T / 4), 0.2, 1e-12);
    EXPECT_NEAR(opacity_at(p, T / 8), 0.125, 1e-12);
    EXPECT_NEAR(opacity_at(p, T / 2), 0.35, 1e-12);
    EXPECT_NEAR(opacity_at(p, 3 * T / 4), 0.2, 1e-12);
    EXPECT_NEAR(opacity_at(p, T), 0.05, 1e-12);
}

TEST(OverlayPulse, StaticStaysAtMax) {
    Preset p = built_in("static");
    for (double t : {0.0, 0.4, 1.0, 123.4}) EXPECT_EQ(opacity_at(p, t), 0.3);
    Preset q = built_in("balanced");
    q.period_s = 0;
    EXPECT_EQ(opacity_at(q, 0.0), 0.4);
}

TEST(OverlayPulse, OnDemandHoldsThenFades) {
    Preset p = built_in("subtle");  // on_demand, fade 3 s
    EXPECT_EQ(presence(p, std::nullopt), 0.0);
    EXPECT_EQ(presence(p, 0.0), 1.0);
    EXPECT_EQ(presence(p, kOnDemandHoldS), 1.0);
    EXPECT_NEAR(presence(p, kOnDemandHoldS + 1.5), 0.5, 1e-12);
    EXPECT_EQ(presence(p, kOnDemandHoldS + 3.0), 0.0);
    EXPECT_EQ(presence(p, 1e9), 0.0);
    EXPECT_EQ(presence(p, std::nan("")), 0.0);
    p.fade_s = 0;
    EXPECT_EQ(presence(p, kOnDemandHoldS + 0.01), 0.0);
    Preset always = built_in("visible");
    EXPECT_EQ(presence(always, std::nullopt), 1.0);
    EXPECT_NEAR(mixed_opacity(built_in("subtle"), 0.75, kOnDemandHoldS + 1.5), 0.25 * 0.5, 1e-12);
}

}  // namespace
