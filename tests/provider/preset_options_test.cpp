// A preset's settings on the command line.
#ifdef UMF_PROVIDER_TESTS

#include <gtest/gtest.h>

#include "provider/commands/preset_options.hpp"

namespace {

using namespace umf::provider;
using umf::cli::UsageError;

umf::cli::Args args(std::vector<std::string> words) {
    std::vector<char*> argv{const_cast<char*>("umf-provider")};
    for (auto& w : words) argv.push_back(w.data());
    return umf::cli::parse_args(static_cast<int>(argv.size()), argv.data(), 1, preset_setting_options(), {});
}

umf::overlay::Preset balanced() {
    const auto presets = umf::overlay::built_in_presets();
    return *umf::overlay::find_preset(presets, "balanced");
}

TEST(PresetOptions, OverrideTheChosenPreset) {
    const auto p = apply_preset_options(
        balanced(), args({"--opacity-min", "0.05", "--opacity-max", "0.2", "--period", "3", "--waveform", "triangle",
                          "--region", "focus", "--focus-radius", "12", "--activation", "always", "--fade", "1",
                          "--palette", "#101010,#f0f0f0", "--module-px", "24", "--blur", "0.5"}));
    EXPECT_DOUBLE_EQ(p.opacity_min, 0.05);
    EXPECT_DOUBLE_EQ(p.opacity_max, 0.2);
    EXPECT_DOUBLE_EQ(p.period_s, 3.0);
    EXPECT_EQ(p.waveform, umf::overlay::Waveform::triangle);
    EXPECT_EQ(p.region, umf::overlay::Region::focus);
    EXPECT_DOUBLE_EQ(p.focus_radius_modules, 12.0);
    EXPECT_EQ(p.activation, umf::overlay::Activation::always);
    EXPECT_EQ(p.palette, (std::vector<std::string>{"#101010", "#f0f0f0"}));
    EXPECT_DOUBLE_EQ(p.module_px, 24.0);
    EXPECT_EQ(p.name, "balanced");
    EXPECT_EQ(apply_preset_options(balanced(), args({})), balanced());
}

TEST(PresetOptions, RefusalsNameTheOption) {
    auto message = [](std::vector<std::string> words) {
        try {
            apply_preset_options(balanced(), args(std::move(words)));
        } catch (const UsageError& e) {
            return std::string(e.what());
        }
        return std::string("accepted");
    };
    EXPECT_NE(message({"--opacity-max", "1.5"}).find("opacity-max"), std::string::npos);
    EXPECT_NE(message({"--waveform", "square"}).find("--waveform"), std::string::npos);
    EXPECT_NE(message({"--palette", "#12345"}).find("--palette"), std::string::npos);
    EXPECT_NE(message({"--period", "0.2"}), "accepted") << "faster than 2 Hz would flash";
    EXPECT_NE(message({"--opacity-min", "0.5", "--opacity-max", "0.2"}), "accepted");
}

}  // namespace

#endif
