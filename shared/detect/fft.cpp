#include "shared/detect/fft.hpp"

#include <cmath>
#include <stdexcept>
#include <utility>

namespace umf {

namespace {

// e^{-2 pi i k / n} for k < n / 2: every span's twiddle factors (a span s
// takes every (n / s)-th), each as exact as one sincos makes it.
std::vector<Complex> twiddles(int n) {
    constexpr double kTwoPi = 6.283185307179586;
    std::vector<Complex> w(static_cast<std::size_t>(n / 2));
    for (int k = 0; k < n / 2; ++k) w[static_cast<std::size_t>(k)] = std::polar(1.0, -kTwoPi * k / n);
    return w;
}

// The transform of n contiguous values, n a power of two.
void transform(Complex* data, int n, const std::vector<Complex>& w) {
    // Bit-reversed order, then butterflies of growing span.
    for (int i = 1, j = 0; i < n; ++i) {
        int bit = n >> 1;
        for (; j & bit; bit >>= 1) j ^= bit;
        j ^= bit;
        if (i < j) std::swap(data[i], data[j]);
    }
    for (int span = 2; span <= n; span <<= 1) {
        const int half = span / 2, every = n / span;
        for (int start = 0; start < n; start += span)
            for (int k = 0; k < half; ++k) {
                // The product written out: the same arithmetic as the
                // complex one for finite values, without its test for NaN
                // on every butterfly.
                Complex& a = data[start + k];
                Complex& b = data[start + k + half];
                const Complex& f = w[static_cast<std::size_t>(k * every)];
                const Complex t(f.real() * b.real() - f.imag() * b.imag(), f.real() * b.imag() + f.imag() * b.real());
                b = a - t;
                a += t;
            }
    }
}

}  // namespace

void fft(Complex* data, int n, int stride) {
    if (!is_power_of_two(n)) throw std::invalid_argument("fft: the length must be a power of two");
    std::vector<Complex> line(static_cast<std::size_t>(n));
    for (int i = 0; i < n; ++i) line[static_cast<std::size_t>(i)] = data[static_cast<std::ptrdiff_t>(i) * stride];
    transform(line.data(), n, twiddles(n));
    for (int i = 0; i < n; ++i) data[static_cast<std::ptrdiff_t>(i) * stride] = line[static_cast<std::size_t>(i)];
}

void fft_2d(std::vector<Complex>& image, int n) { fft_2d(image, n, n, 0); }

void fft_2d(std::vector<Complex>& image, int n, int low_columns, int high_columns) {
    if (!is_power_of_two(n)) throw std::invalid_argument("fft: the length must be a power of two");
    if (static_cast<long>(image.size()) != static_cast<long>(n) * n)
        throw std::invalid_argument("fft_2d: the image must hold n x n values");
    const std::vector<Complex> w = twiddles(n);
    for (int y = 0; y < n; ++y) transform(image.data() + static_cast<std::ptrdiff_t>(y) * n, n, w);
    // Each column through a contiguous line: a stride of n values misses the
    // cache on every butterfly.
    std::vector<Complex> column(static_cast<std::size_t>(n));
    for (int x = 0; x < n; ++x) {
        if (x >= low_columns && x < n - high_columns) continue;
        for (int y = 0; y < n; ++y) column[static_cast<std::size_t>(y)] = image[static_cast<std::size_t>(y) * n + x];
        transform(column.data(), n, w);
        for (int y = 0; y < n; ++y) image[static_cast<std::size_t>(y) * n + x] = column[static_cast<std::size_t>(y)];
    }
}

}  // namespace umf
