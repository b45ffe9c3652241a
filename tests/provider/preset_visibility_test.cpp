// How much of each built-in preset a person at the screen can see: the
// demo board composed as the provider shows it, at the pulse's lowest and
// highest opacity and without the field, compared pixel by pixel in 8-bit
// grey levels (BT.601 luma). The figures go to docs/BENCHMARKS.md; the
// invisible preset must stay within a few levels.
#ifdef UMF_PROVIDER_TESTS

#include <gtest/gtest.h>

#include <QImage>
#include <algorithm>
#include <cstdio>
#include <string>
#include <vector>

#include "provider/board/board.hpp"
#include "provider/screen/screen_field.hpp"
#include "provider/screen/screen_image.hpp"
#include "shared/overlay/preset.hpp"
#include "shared/overlay/pulse.hpp"
#include "tests/provider/gui_test_app.hpp"
#include "tests/support/temp_dir.hpp"

namespace umf::provider {
namespace {

std::vector<int> luma(const QImage& image) {
    const QImage rgb = image.convertToFormat(QImage::Format_RGB888);
    std::vector<int> out;
    out.reserve(static_cast<std::size_t>(rgb.width()) * static_cast<std::size_t>(rgb.height()));
    for (int y = 0; y < rgb.height(); ++y) {
        const uchar* p = rgb.constScanLine(y);
        for (int x = 0; x < rgb.width(); ++x, p += 3) out.push_back((77 * p[0] + 150 * p[1] + 29 * p[2] + 128) >> 8);
    }
    return out;
}

// How far apart two images' grey levels are: the mean over the pixels, the
// 99th percentile and the largest.
struct Change {
    double mean = 0;
    int p99 = 0;
    int most = 0;
};

Change change(const std::vector<int>& a, const std::vector<int>& b) {
    std::vector<int> d(a.size());
    double sum = 0;
    for (std::size_t i = 0; i < a.size(); ++i) {
        d[i] = std::abs(a[i] - b[i]);
        sum += d[i];
    }
    Change c;
    c.mean = a.empty() ? 0 : sum / static_cast<double>(a.size());
    c.most = d.empty() ? 0 : *std::max_element(d.begin(), d.end());
    const auto at = d.begin() + static_cast<std::ptrdiff_t>(d.size() * 99 / 100);
    std::nth_element(d.begin(), at, d.end());
    c.p99 = d.empty() ? 0 : *at;
    return c;
}

TEST(PresetVisibility, TheInvisiblePulseChangesTheScreenByAFewGreyLevels) {
    test::ensure_gui_application();
    test::TempDir dir;
    const Board board = write_demo_board(dir.path / "demo");
    const QSize size(1920, 1080);
    std::vector<std::pair<std::string, Change>> pulses;
    for (const overlay::Preset& p : overlay::built_in_presets()) {
        const ScreenField field = screen_field_for(size.width(), size.height(), p.module_px);
        auto at = [&](double opacity) { return luma(compose_screen(nullptr, &board, size, field, opacity, p.palette)); };
        const std::vector<int> content = at(0);
        const std::vector<int> low = at(overlay::opacity_at(p, 0));
        const std::vector<int> high = at(overlay::opacity_at(p, p.period_s / 2));
        const Change pulse = change(low, high), shown = change(content, high);
        std::printf("[ measure  ] preset %-9s opacity %.2f..%.2f: the pulse moves a pixel by %.2f grey levels on "
                    "average (99th percentile %d, at most %d); at its top the field differs from the content by "
                    "%.2f (99th percentile %d, at most %d)\n",
                    p.name.c_str(), p.opacity_min, p.opacity_max, pulse.mean, pulse.p99, pulse.most, shown.mean,
                    shown.p99, shown.most);
        pulses.emplace_back(p.name, pulse);
        if (p.name != "invisible") continue;
        // 255 x 0.03 and 255 x 0.04, rounded: the pulse and the field at its top.
        EXPECT_LE(pulse.most, 8);
        EXPECT_LE(shown.most, 11);
        EXPECT_GE(pulse.p99, 1) << "the pulse is there";
    }
    // Every other pulsing preset moves the screen more than the invisible one.
    const auto invisible = std::find_if(pulses.begin(), pulses.end(), [](const auto& e) { return e.first == "invisible"; });
    ASSERT_NE(invisible, pulses.end());
    for (const auto& [name, c] : pulses) {
        if (name == "invisible" || name == "static") continue;
        EXPECT_GT(c.mean, invisible->second.mean) << name;
    }
}

}  // namespace
}  // namespace umf::provider

#endif
