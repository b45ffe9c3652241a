// The field's module edges by row (module_edges.hpp): the edges of any
// block of modules, spread evenly, as walking the block module by module
// gives them.
#include "shared/detect/module_edges.hpp"

#include <gtest/gtest.h>

#include <random>

#include "shared/field/field_io.hpp"
#include "tests/support/shipped_field.hpp"

using namespace umf;
using umf::test::shipped_field;

namespace {

// Module by module over the block, every edge, then every k-th.
std::vector<ExpectedEdge> walked(const Field& f, int r0, int r1, int c0, int c1, std::size_t most) {
    const std::vector<double> b = module_brightness(f);
    std::vector<ExpectedEdge> all;
    for (int r = r0; r <= r1; ++r)
        for (int c = c0; c <= c1; ++c) {
            if (c > 0 && b[f.at(r, c)] != b[f.at(r, c - 1)])
                all.push_back({Point2(c, r + 0.5), Point2(1, 0), b[f.at(r, c)] > b[f.at(r, c - 1)] ? 1.0 : -1.0});
            if (r > 0 && b[f.at(r, c)] != b[f.at(r - 1, c)])
                all.push_back({Point2(c + 0.5, r), Point2(0, 1), b[f.at(r, c)] > b[f.at(r - 1, c)] ? 1.0 : -1.0});
        }
    const std::size_t stride = std::max<std::size_t>(1, (all.size() + most - 1) / most);
    std::vector<ExpectedEdge> out;
    for (std::size_t i = 0; i < all.size(); i += stride) out.push_back(all[i]);
    return out;
}

TEST(ModuleEdges, AnyBlockSpreadAsWalkingItGivesIt) {
    for (const char* name : {"b4-64x36.json", "b4-96x54.json", "k3e4-64x36.json"}) {
        const Field f = shipped_field(name);
        const ModuleEdges edges(f);
        std::mt19937 rng(7);
        std::vector<ExpectedEdge> got;
        for (int trial = 0; trial < 300; ++trial) {
            int r0 = static_cast<int>(rng() % f.height), r1 = static_cast<int>(rng() % f.height);
            int c0 = static_cast<int>(rng() % f.width), c1 = static_cast<int>(rng() % f.width);
            if (trial % 3 == 0) std::swap(r0, r1);  // an empty block now and then
            if (r0 > r1 && trial % 3 != 0) std::swap(r0, r1);
            if (c0 > c1) std::swap(c0, c1);
            const std::size_t most = trial % 4 == 0 ? 100000 : 1 + rng() % 120;
            edges.spread_within(r0, r1, c0, c1, most, got);
            const std::vector<ExpectedEdge> want = r0 > r1 ? std::vector<ExpectedEdge>{} : walked(f, r0, r1, c0, c1, most);
            ASSERT_EQ(got.size(), want.size()) << name << " rows " << r0 << ".." << r1 << " cols " << c0 << ".." << c1;
            EXPECT_LE(got.size(), most);
            for (std::size_t i = 0; i < got.size(); ++i) {
                EXPECT_EQ(got[i].mid, want[i].mid);
                EXPECT_EQ(got[i].across, want[i].across);
                EXPECT_EQ(got[i].polarity, want[i].polarity);
            }
        }
        // The whole field: every edge between modules that differ.
        edges.spread_within(0, f.height - 1, 0, f.width - 1, 1000000, got);
        EXPECT_EQ(got.size(), walked(f, 0, f.height - 1, 0, f.width - 1, 1000000).size());
        EXPECT_GT(got.size(), static_cast<std::size_t>(f.width * f.height / 2));
    }
}

}  // namespace
