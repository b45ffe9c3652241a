#include "shared/detect/fft.hpp"

#include <cmath>
#include <stdexcept>
#include <utility>

namespace umf {

void fft(Complex* data, int n, int stride) {
    if (!is_power_of_two(n)) throw std::invalid_argument("fft: the length must be a power of two");
    const auto at = [&](int i) -> Complex& { return data[static_cast<std::ptrdiff_t>(i) * stride]; };
    // Bit-reversed order, then butterflies of growing span.
    for (int i = 1, j = 0; i < n; ++i) {
        int bit = n >> 1;
        for (; j & bit; bit >>= 1) j ^= bit;
        j ^= bit;
        if (i < j) std::swap(at(i), at(j));
    }
    constexpr double kTwoPi = 6.283185307179586;
    for (int span = 2; span <= n; span <<= 1) {
        const Complex step = std::polar(1.0, -kTwoPi / span);
        for (int start = 0; start < n; start += span) {
            Complex w = 1;
            for (int k = 0; k < span / 2; ++k) {
                Complex& a = at(start + k);
                Complex& b = at(start + k + span / 2);
                const Complex t = w * b;
                b = a - t;
                a += t;
                w *= step;
            }
        }
    }
}

void fft_2d(std::vector<Complex>& image, int n) {
    if (static_cast<long>(image.size()) != static_cast<long>(n) * n)
        throw std::invalid_argument("fft_2d: the image must hold n x n values");
    for (int y = 0; y < n; ++y) fft(image.data() + static_cast<std::ptrdiff_t>(y) * n, n, 1);
    for (int x = 0; x < n; ++x) fft(image.data() + x, n, n);
}

}  // namespace umf
