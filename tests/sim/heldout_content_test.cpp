// Tests of the held-out screen contents: deterministic, of the asked size,
// different from each other and each with its defining look.
#include <gtest/gtest.h>

#include <opencv2/core.hpp>
#include <opencv2/imgproc.hpp>

#include "tests/sim/heldout_content.hpp"

namespace {

using namespace umf::sim;

const cv::Size kSize{1280, 800};

TEST(SimHeldoutContent, DeterministicSizedAndDistinct) {
    std::vector<cv::Mat> all;
    for (HeldoutContent c : kAllHeldoutContents) {
        const cv::Mat a = make_heldout_screen(c, kSize, 3);
        ASSERT_EQ(a.size(), kSize) << to_string(c);
        ASSERT_EQ(a.type(), CV_8UC3);
        EXPECT_EQ(cv::norm(a, make_heldout_screen(c, kSize, 3), cv::NORM_INF), 0) << to_string(c);
        EXPECT_GT(cv::norm(a, make_heldout_screen(c, kSize, 4), cv::NORM_L1), 0) << to_string(c);
        for (const auto& other : all) EXPECT_GT(cv::norm(a, other, cv::NORM_L1) / a.total(), 10) << to_string(c);
        all.push_back(a);
    }
}

TEST(SimHeldoutContent, EachKindLooksItsPart) {
    const auto mean_grey = [](const cv::Mat& m) {
        cv::Mat g;
        cv::cvtColor(m, g, cv::COLOR_BGR2GRAY);
        return cv::mean(g)[0];
    };
    EXPECT_GT(mean_grey(make_heldout_screen(HeldoutContent::spreadsheet, kSize, 1)), 200);
    EXPECT_LT(mean_grey(make_heldout_screen(HeldoutContent::dark_editor, kSize, 1)), 60);
    const cv::Mat video = make_heldout_screen(HeldoutContent::video_frame, kSize, 1);
    EXPECT_EQ(cv::countNonZero(video.rowRange(0, 20).reshape(1)), 0);  // letterbox bar
    // The spreadsheet's grid: many rows that are one long grey line.
    const cv::Mat sheet = make_heldout_screen(HeldoutContent::spreadsheet, kSize, 1);
    int grid_rows = 0;
    for (int y = 0; y < sheet.rows; ++y) {
        int grey = 0;
        for (int x = 0; x < sheet.cols; ++x) grey += sheet.at<cv::Vec3b>(y, x)[1] < 225;
        grid_rows += grey > sheet.cols / 2;
    }
    EXPECT_GT(grid_rows, 15);
}

}  // namespace
