// Tests of the synthetic screen contents.
#include <gtest/gtest.h>

#include <opencv2/core.hpp>

#include "tests/sim/screen_content.hpp"

namespace {

using namespace umf::sim;

const cv::Size kScreenSize{640, 360};

TEST(SimScreenContent, DeterministicPerSeed) {
    for (ScreenKind kind : kAllScreenKinds) {
        const cv::Mat a = make_screen(kind, kScreenSize, 5);
        ASSERT_EQ(a.size(), kScreenSize) << to_string(kind);
        ASSERT_EQ(a.type(), CV_8UC3) << to_string(kind);
        EXPECT_EQ(cv::norm(a, make_screen(kind, kScreenSize, 5), cv::NORM_INF), 0) << to_string(kind);
        if (kind != ScreenKind::blank) {
            EXPECT_GT(cv::norm(a, make_screen(kind, kScreenSize, 6), cv::NORM_L1), 0) << to_string(kind);
        }
    }
}

TEST(SimScreenContent, KindsDiffer) {
    for (std::size_t i = 0; i < kAllScreenKinds.size(); ++i)
        for (std::size_t j = i + 1; j < kAllScreenKinds.size(); ++j)
            EXPECT_GT(cv::norm(make_screen(kAllScreenKinds[i], kScreenSize, 1), make_screen(kAllScreenKinds[j], kScreenSize, 1),
                               cv::NORM_L1) / (kScreenSize.area() * 3.0),
                      10)
                << to_string(kAllScreenKinds[i]) << " vs " << to_string(kAllScreenKinds[j]);
}

TEST(SimScreenContent, KindsLookTheirPart) {
    EXPECT_GT(cv::mean(make_screen(ScreenKind::document, kScreenSize, 1))[0], 200);   // white page
    EXPECT_LT(cv::mean(make_screen(ScreenKind::code_dark, kScreenSize, 1))[1], 80);   // dark theme
    EXPECT_EQ(cv::mean(make_screen(ScreenKind::blank, kScreenSize, 1)), cv::Scalar(128, 128, 128, 0));
    cv::Scalar mean, stddev;
    cv::meanStdDev(make_screen(ScreenKind::photo, kScreenSize, 1), mean, stddev);
    EXPECT_GT(stddev[1], 25);  // busy everywhere
}

}  // namespace
