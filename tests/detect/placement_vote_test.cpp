#include "shared/detect/placement_vote.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <utility>

#include "shared/field/field_io.hpp"
#include "tests/support/shipped_field.hpp"

using namespace umf;
using umf::test::shipped_field;

namespace {

// The field region of h x w modules at (r0, c0), turned clockwise t times as a
// camera would see it; `source` gets the field module each grid cell shows.
ModuleGrid turned_region(const Field& f, int r0, int c0, int h, int w, int t,
                         std::vector<std::pair<int, int>>& source) {
    std::vector<std::pair<int, int>> cells;
    int rows = h, cols = w;
    for (int i = 0; i < h; ++i)
        for (int j = 0; j < w; ++j) cells.emplace_back(r0 + i, c0 + j);
    for (int k = 0; k < t; ++k) {  // turning clockwise: new (i, j) shows old (rows-1-j, i)
        std::vector<std::pair<int, int>> turned(cells.size());
        for (int i = 0; i < cols; ++i)
            for (int j = 0; j < rows; ++j) turned[i * rows + j] = cells[(rows - 1 - j) * cols + i];
        cells.swap(turned);
        std::swap(rows, cols);
    }
    ModuleGrid g(rows, cols);
    for (int i = 0; i < rows; ++i)
        for (int j = 0; j < cols; ++j) {
            auto [r, c] = cells[i * cols + j];
            g.at(i, j) = static_cast<std::int8_t>(f.at(r, c));
        }
    g.derive_edges();
    source = cells;
    return g;
}

void expect_placement(const ModuleGrid& g, const VoteResult& v, const std::vector<std::pair<int, int>>& source) {
    ASSERT_TRUE(v.found) << "votes " << v.votes << " runner-up " << v.runner_up << " agreement " << v.agreement;
    for (int i = 0; i < g.rows; ++i)
        for (int j = 0; j < g.cols; ++j) {
            int r, c;
            v.placement.field_module(i, j, r, c);
            ASSERT_EQ(r, source[i * g.cols + j].first) << "cell " << i << "," << j;
            ASSERT_EQ(c, source[i * g.cols + j].second) << "cell " << i << "," << j;
        }
}

TEST(WindowIndex, FindsEveryWindowUnderEveryTurn) {
    for (const char* name : {"b4-64x36.json", "k3e4-64x36.json", "k5e3-64x36.json"}) {
        Field f = shipped_field(name);
        WindowIndex index(f);
        for (int r = 0; r < f.window_rows(); r += 3)
            for (int c = 0; c < f.window_cols(); c += 2)
                for (int t = 0; t < 4; ++t) {
                    auto m = index.find(index.codec().code_at(f, r, c, t));
                    ASSERT_TRUE(m) << name;
                    EXPECT_EQ(m->row, r);
                    EXPECT_EQ(m->col, c);
                    EXPECT_EQ(m->quarter_turns, t);
                }
    }
}

TEST(WindowIndex, RefusesFieldsThatAreNotOrientable) {
    Field f = make_field(8, 8, 4, 2, WindowKey::modules);  // all zero
    EXPECT_THROW(WindowIndex{f}, std::invalid_argument);
}

TEST(PlacementVote, FindsPositionAndTurnOfAnyRegion) {
    for (const char* name : {"b4-64x36.json", "k3e4-64x36.json", "k5e3-64x36.json"}) {
        Field f = shipped_field(name);
        WindowIndex index(f);
        std::mt19937 rng(1);
        for (int trial = 0; trial < 40; ++trial) {
            const int h = 7 + static_cast<int>(rng() % 8), w = 7 + static_cast<int>(rng() % 8);
            const int r0 = static_cast<int>(rng() % (f.height - h + 1)), c0 = static_cast<int>(rng() % (f.width - w + 1));
            const int t = trial % 4;
            std::vector<std::pair<int, int>> source;
            ModuleGrid g = turned_region(f, r0, c0, h, w, t, source);
            auto v = vote_placement(g, index);
            expect_placement(g, v, source);
            EXPECT_EQ(v.placement.quarter_turns, t) << name;
            EXPECT_DOUBLE_EQ(v.agreement, 1.0);
            EXPECT_EQ(v.votes, v.windows_read);
        }
    }
}

TEST(PlacementVote, FieldPointsFollowTheModules) {
    Field f = shipped_field("b4-64x36.json");
    WindowIndex index(f);
    for (int t = 0; t < 4; ++t) {
        std::vector<std::pair<int, int>> source;
        ModuleGrid g = turned_region(f, 10, 20, 6, 9, t, source);
        auto v = vote_placement(g, index);
        ASSERT_TRUE(v.found);
        for (int i = 0; i < g.rows; ++i)
            for (int j = 0; j < g.cols; ++j) {
                double u, vv;
                v.placement.field_point(j + 0.5, i + 0.5, u, vv);
                EXPECT_EQ(static_cast<int>(std::floor(u)), source[i * g.cols + j].second);
                EXPECT_EQ(static_cast<int>(std::floor(vv)), source[i * g.cols + j].first);
            }
        // Corners of the grid land on module corners, and the grid's area is kept.
        double u0, v0, u1, v1;
        v.placement.field_point(0, 0, u0, v0);
        v.placement.field_point(g.cols, g.rows, u1, v1);
        EXPECT_DOUBLE_EQ(std::abs((u1 - u0) * (v1 - v0)), static_cast<double>(g.rows * g.cols));
    }
}

// Found at most `misread` and `unread` per cent of modules wrong or missing:
// returns how many of `trials` 12 x 12 grids were placed; each placed one must be right.
int place_noisy_grids(const char* name, int misread, int unread, int trials) {
    Field f = shipped_field(name);
    WindowIndex index(f);
    std::mt19937 rng(2);
    int found = 0;
    for (int trial = 0; trial < trials; ++trial) {
        std::vector<std::pair<int, int>> source;
        const int r0 = static_cast<int>(rng() % (f.height - 11)), c0 = static_cast<int>(rng() % (f.width - 11));
        ModuleGrid g = turned_region(f, r0, c0, 12, 12, trial % 4, source);
        for (auto& m : g.value) {
            const int roll = static_cast<int>(rng() % 100);
            if (roll < misread)
                m = static_cast<std::int8_t>((m + 1 + rng() % (f.colors - 1)) % f.colors);
            else if (roll < misread + unread)
                m = ModuleGrid::kUnknown;
        }
        g.derive_edges();
        auto v = vote_placement(g, index);
        if (!v.found) continue;
        ++found;
        expect_placement(g, v, source);  // found means right
    }
    return found;
}

TEST(PlacementVote, ToleratesMisreadAndUnreadModules) {
    EXPECT_GE(place_noisy_grids("b4-64x36.json", 3, 3, 100), 97);
    EXPECT_GE(place_noisy_grids("b4-64x36.json", 6, 6, 100), 75);
    EXPECT_GE(place_noisy_grids("k3e4-64x36.json", 2, 2, 100), 90);
}

// vote_near counts a module-keyed grid's agreeing windows from the modules
// themselves, without looking them up: the same windows the whole vote
// counts for that placement, with the same centre, wherever the grid
// reaches past the field's edge, with misread and unread modules, under
// every turn.
TEST(PlacementVote, VoteNearCountsTheWindowsTheWholeVoteCounts) {
    for (const char* name : {"b4-64x36.json", "k3e4-64x36.json"}) {
        Field f = shipped_field(name);
        WindowIndex index(f);
        std::mt19937 rng(5);
        int compared = 0;
        for (int trial = 0; trial < 200; ++trial) {
            std::vector<std::pair<int, int>> source;
            const int r0 = static_cast<int>(rng() % (f.height - 13)), c0 = static_cast<int>(rng() % (f.width - 15));
            ModuleGrid g = turned_region(f, r0, c0, 13, 15, trial % 4, source);
            for (auto& m : g.value) {
                const int roll = static_cast<int>(rng() % 100);
                if (roll < 4)
                    m = static_cast<std::int8_t>((m + 1 + rng() % (f.colors - 1)) % f.colors);
                else if (roll < 8)
                    m = ModuleGrid::kUnknown;
            }
            g.derive_edges();
            const VoteResult whole = vote_placement(g, index);
            if (whole.votes < 2) continue;
            // Predicted one module off, so that part of the grid lies off the field under some placements.
            GridPlacement predicted = whole.placement;
            predicted.row_offset += 1;
            const VoteResult near = vote_near(g, index, predicted, 2);
            ASSERT_EQ(near.placement, whole.placement) << name << " trial " << trial;
            EXPECT_EQ(near.votes, whole.votes) << name << " trial " << trial;
            EXPECT_DOUBLE_EQ(near.centre_x, whole.centre_x) << name << " trial " << trial;
            EXPECT_DOUBLE_EQ(near.centre_y, whole.centre_y) << name << " trial " << trial;
            ++compared;
        }
        EXPECT_GE(compared, 150) << name;
    }
}

TEST(PlacementVote, NeverPlacesRandomGrids) {
    for (const char* name : {"b4-64x36.json", "k3e4-64x36.json"}) {
        Field f = shipped_field(name);
        WindowIndex index(f);
        std::mt19937 rng(3);
        for (int trial = 0; trial < 1000; ++trial) {
            ModuleGrid g(4 + static_cast<int>(rng() % 12), 4 + static_cast<int>(rng() % 12));
            for (auto& m : g.value) m = static_cast<std::int8_t>(rng() % f.colors);
            g.derive_edges();
            EXPECT_FALSE(vote_placement(g, index).found) << name << " trial " << trial;
        }
    }
}

TEST(PlacementVote, NeverPlacesAnotherFieldsRegion) {
    Field a = shipped_field("b4-64x36.json"), b = shipped_field("b4-96x54.json");
    WindowIndex index(a);
    std::mt19937 rng(4);
    for (int trial = 0; trial < 300; ++trial) {
        std::vector<std::pair<int, int>> source;
        ModuleGrid g = turned_region(b, static_cast<int>(rng() % 40), static_cast<int>(rng() % 80), 10, 10,
                                     trial % 4, source);
        EXPECT_FALSE(vote_placement(g, index).found) << "trial " << trial;
    }
}

TEST(PlacementVote, FewModulesInViewAreNotEnough) {
    Field f = shipped_field("b4-64x36.json");
    WindowIndex index(f);
    std::vector<std::pair<int, int>> source;
    ModuleGrid g = turned_region(f, 3, 3, 4, 4, 0, source);
    auto v = vote_placement(g, index);
    EXPECT_EQ(v.votes, 1);
    EXPECT_FALSE(v.found);
    // Two agreeing windows in a 4 x 5 grid are 20 modules: a random grid does that
    // about once in a few hundred tries, so it is not evidence enough.
    g = turned_region(f, 3, 3, 4, 5, 0, source);
    v = vote_placement(g, index);
    EXPECT_EQ(v.votes, 2);
    EXPECT_FALSE(v.found);
    g = turned_region(f, 3, 3, 6, 6, 0, source);
    v = vote_placement(g, index);
    EXPECT_TRUE(v.found) << v.evidence_bits;
}

}  // namespace
