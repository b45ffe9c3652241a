// The radix-2 FFT against the sums it stands for.
#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <stdexcept>

#include "shared/detect/fft.hpp"

namespace {

using umf::Complex;

Complex naive(const std::vector<Complex>& x, int k) {
    const int n = static_cast<int>(x.size());
    Complex sum = 0;
    for (int j = 0; j < n; ++j) sum += x[static_cast<std::size_t>(j)] * std::polar(1.0, -2 * M_PI * k * j / n);
    return sum;
}

TEST(Fft, MatchesTheDiscreteFourierSum) {
    std::mt19937 rng(3);
    std::uniform_real_distribution<double> u(-1, 1);
    for (int n : {1, 2, 4, 16, 64}) {
        std::vector<Complex> x(static_cast<std::size_t>(n));
        for (auto& v : x) v = {u(rng), u(rng)};
        std::vector<Complex> y = x;
        umf::fft(y.data(), n);
        for (int k = 0; k < n; ++k) EXPECT_LT(std::abs(y[static_cast<std::size_t>(k)] - naive(x, k)), 1e-9) << n << " " << k;
    }
}

TEST(Fft, TwoDimensionsFindAPlaneWavesFrequency) {
    const int n = 32;
    std::vector<Complex> image(static_cast<std::size_t>(n) * n);
    for (int y = 0; y < n; ++y)
        for (int x = 0; x < n; ++x) image[static_cast<std::size_t>(y) * n + x] = std::cos(2 * M_PI * (3.0 * x + 5.0 * y) / n);
    umf::fft_2d(image, n);
    // A cosine is two conjugate waves: half the energy at (3, 5), half at (-3, -5).
    EXPECT_NEAR(std::abs(image[5 * n + 3]), n * n / 2.0, 1e-6);
    EXPECT_NEAR(std::abs(image[static_cast<std::size_t>(n - 5) * n + (n - 3)]), n * n / 2.0, 1e-6);
    EXPECT_LT(std::abs(image[5 * n + 4]), 1e-6);
}

TEST(Fft, TwoDimensionsOverSomeColumnsMatchTheWholeTransformThere) {
    const int n = 16;
    std::mt19937 rng(5);
    std::uniform_real_distribution<double> u(-1, 1);
    std::vector<Complex> image(static_cast<std::size_t>(n) * n);
    for (auto& v : image) v = u(rng);
    std::vector<Complex> whole = image, some = image, rows_only = image;
    umf::fft_2d(whole, n);
    umf::fft_2d(some, n, 9, 1);
    umf::fft_2d(rows_only, n, 0, 0);
    for (int y = 0; y < n; ++y)
        for (int x = 0; x < n; ++x) {
            const std::size_t i = static_cast<std::size_t>(y) * n + x;
            if (x < 9 || x == n - 1)
                EXPECT_EQ(some[i], whole[i]) << x << " " << y;  // the same arithmetic, bit for bit
            else
                EXPECT_EQ(some[i], rows_only[i]) << x << " " << y;
        }
    // The rows alone are each row's 1-D transform.
    std::vector<Complex> row(image.begin() + 3 * n, image.begin() + 4 * n);
    for (int k = 0; k < n; ++k) EXPECT_LT(std::abs(rows_only[3 * n + static_cast<std::size_t>(k)] - naive(row, k)), 1e-9);
}

TEST(Fft, RefusesLengthsThatAreNotPowersOfTwo) {
    std::vector<Complex> x(12);
    EXPECT_THROW(umf::fft(x.data(), 12), std::invalid_argument);
    std::vector<Complex> image(9);
    EXPECT_THROW(umf::fft_2d(image, 3), std::invalid_argument);
    EXPECT_THROW(umf::fft_2d(image, 4), std::invalid_argument);  // 9 values are not 4 x 4
}

}  // namespace
