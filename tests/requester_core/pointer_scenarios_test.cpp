// The requester core's scenarios (tests/data/requester_core/*.json): each
// step is an event and what must come of it ("expect"), or an event the
// core must refuse ("refused": a provider's message that breaks the protocol). The phone page's copy of the
// core, compiled to WebAssembly, runs the very same files
// (tests/web/requester_core_scenarios.mjs).
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <stdexcept>

#include "shared/requester_core/pointer_json.hpp"

namespace umf::requester_core {
namespace {

using nlohmann::json;
namespace fs = std::filesystem;

const fs::path kScenarios = fs::path(UMF_TEST_DATA_DIR) / "requester_core";

json read_json(const fs::path& path) {
    std::ifstream in(path);
    if (!in) throw std::runtime_error("cannot read " + path.string());
    return json::parse(in);
}

// `expected` holds only what matters: every key it has must match (null:
// absent or null), arrays element by element and of the same length,
// numbers to 1e-9. Returns where they differ, or empty.
std::string difference(const json& expected, const json& actual, const std::string& at) {
    if (expected.is_null()) return actual.is_null() ? "" : at + ": expected null, got " + actual.dump();
    if (expected.is_object()) {
        if (!actual.is_object()) return at + ": expected an object, got " + actual.dump();
        for (const auto& [key, value] : expected.items()) {
            const auto it = actual.find(key);
            if (it == actual.end()) {
                if (value.is_null()) continue;
                return at + "." + key + ": missing";
            }
            if (auto m = difference(value, *it, at + "." + key); !m.empty()) return m;
        }
        return "";
    }
    if (expected.is_array()) {
        if (!actual.is_array() || actual.size() != expected.size())
            return at + ": expected " + expected.dump() + ", got " + actual.dump();
        for (std::size_t i = 0; i < expected.size(); ++i)
            if (auto m = difference(expected[i], actual[i], at + "[" + std::to_string(i) + "]"); !m.empty()) return m;
        return "";
    }
    if (expected.is_number() && actual.is_number())
        return std::abs(expected.get<double>() - actual.get<double>()) <= 1e-9
                   ? ""
                   : at + ": expected " + expected.dump() + ", got " + actual.dump();
    return expected == actual ? "" : at + ": expected " + expected.dump() + ", got " + actual.dump();
}

json setup_for(const json& scenario) {
    json setup{{"welcome", read_json(kScenarios / "welcome.json")}};
    for (const char* key : {"auto", "timing"})
        if (scenario.contains(key)) setup[key] = scenario[key];
    return setup;
}

class Scenario : public testing::TestWithParam<std::string> {};

TEST_P(Scenario, EveryStepGivesWhatItExpects) {
    const json scenario = read_json(kScenarios / (GetParam() + ".json"));
    Pointer pointer = pointer_from_json(setup_for(scenario));
    int index = 0;
    for (const json& step : scenario.at("steps")) {
        if (step.value("refused", false)) {
            EXPECT_THROW(apply_json_event(pointer, step.at("event")), std::invalid_argument)
                << GetParam() << ", step " << index;
            ++index;
            continue;
        }
        const json answer = apply_json_event(pointer, step.at("event"));
        if (step.contains("expect")) {
            EXPECT_EQ(difference(step["expect"], answer, "answer"), "")
                << GetParam() << ", step " << index << ": " << step["event"].dump();
        }
        ++index;
    }
}

std::vector<std::string> scenario_names() {
    std::vector<std::string> names;
    for (const auto& entry : fs::directory_iterator(kScenarios))
        if (entry.path().extension() == ".json" && entry.path().stem() != "welcome")
            names.push_back(entry.path().stem().string());
    std::sort(names.begin(), names.end());
    return names;
}

INSTANTIATE_TEST_SUITE_P(RequesterCore, Scenario, testing::ValuesIn(scenario_names()),
                         [](const testing::TestParamInfo<std::string>& info) { return info.param; });

TEST(RequesterCore, TheMatcherSeesADifference) {
    const auto differ = [](const char* expected, const char* actual) {
        return !difference(json::parse(expected), json::parse(actual), "answer").empty();
    };
    EXPECT_TRUE(differ(R"({"send": [{"type": "aim"}]})", R"({"send": []})"));
    EXPECT_TRUE(differ(R"({"view": {"phase": "locked"}})", R"({"view": {"phase": "searching", "hint": false}})"));
    EXPECT_TRUE(differ(R"({"x": null})", R"({"x": 1})"));
    EXPECT_TRUE(differ(R"({"x": 0.5})", R"({"x": 0.5001})"));
    EXPECT_FALSE(differ(R"({"x": null})", R"({})"));
    EXPECT_FALSE(differ(R"({"view": {"phase": "locked"}})", R"({"view": {"phase": "locked", "hint": true}})"));
}

TEST(RequesterCore, TheWelcomesLimitSlowsTheAims) {
    json setup = setup_for(json::object());
    setup["welcome"]["limits"]["aims_per_s"] = 2.0;
    Pointer pointer = pointer_from_json(setup);
    int aims = 0;
    for (int i = 0; i < 30; ++i)  // 3 s at 10 frames a second
        aims += static_cast<int>(pointer.frame(i * 0.1, Sighting{true, {1, 1}, 1.0, {}}).send.size());
    EXPECT_EQ(aims, 6);
}

TEST(RequesterCore, APutNeedsAnHttpLinkOrANamedFile) {
    Pointer pointer = pointer_from_json(setup_for(json::object()));
    PutItem link;
    link.url = "javascript:alert(1)";
    EXPECT_THROW(pointer.choose_put(0, link), std::invalid_argument);
    PutItem nameless;
    nameless.kind = protocol::ContentKind::file;
    nameless.size = 3;
    EXPECT_THROW(pointer.choose_put(0, nameless), std::invalid_argument);
    PutItem snapshot;
    snapshot.kind = protocol::ContentKind::snapshot;
    EXPECT_THROW(pointer.choose_put(0, snapshot), std::invalid_argument);
    EXPECT_EQ(pointer.view().mode, Mode::grab);
}

TEST(RequesterCore, AMessageThatBreaksTheProtocolIsRefusedByName) {
    Pointer pointer = pointer_from_json(setup_for(json::object()));
    const auto apply = [&](const char* event) { return apply_json_event(pointer, json::parse(event)); };
    EXPECT_THROW(apply(R"({"event": "message", "message": {"type": "content", "v": 1}})"), std::invalid_argument);
    EXPECT_THROW(apply(R"({"event": "jump"})"), std::invalid_argument);
    EXPECT_THROW(apply(R"({"event": "frame", "locked": true})"), std::exception);
}

}  // namespace
}  // namespace umf::requester_core
