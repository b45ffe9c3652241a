// The bench scene's screens of every kind (tests/bench/scenario.hpp), without
// the field and with it mixed in at one opacity, ready to be photographed
// many times: what the detector tests that shoot the tuning set's
// categories start from.
#pragma once

#include <vector>

#include "tests/bench/scenario.hpp"
#include "tests/sim/field_mix.hpp"

namespace umf::test {

struct SceneScreens {
    std::vector<cv::Mat> bare;                   // by sim::ScreenKind
    std::vector<sim::ScreenSource> with_field;  // the same, the field mixed in

    SceneScreens(const bench::Scene& scene, const Field& field, double opacity) {
        const sim::FieldPlacement placement{{0, 0}, scene.module_px};
        for (auto kind : sim::kAllScreenKinds) {
            bare.push_back(sim::make_screen(kind, scene.screen.pixels, 7));
            with_field.emplace_back(sim::mix_field(bare.back(), field, placement, opacity), scene.screen);
        }
    }
    const cv::Mat& bare_of(sim::ScreenKind kind) const { return bare[static_cast<std::size_t>(kind)]; }
    const sim::ScreenSource& with_field_of(sim::ScreenKind kind) const {
        return with_field[static_cast<std::size_t>(kind)];
    }
};

}  // namespace umf::test
