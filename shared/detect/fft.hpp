// A radix-2 fast Fourier transform, for the lattice search (lattice.hpp):
// small square images whose side is a power of two.
#pragma once

#include <complex>
#include <vector>

namespace umf {

using Complex = std::complex<double>;

inline bool is_power_of_two(int n) { return n > 0 && (n & (n - 1)) == 0; }

// The forward transform, sum of x[j] e^{-2 pi i k j / n}, in place over the
// n values data[0], data[stride], ... Throws std::invalid_argument unless n
// is a power of two.
void fft(Complex* data, int n, int stride = 1);

// The 2-D forward transform of an n x n image stored row by row.
void fft_2d(std::vector<Complex>& image, int n);

// The same, with only the columns x < `low_columns` and x >= n -
// `high_columns` transformed after the rows (the others hold the rows'
// transforms alone): what a spectrum read over a band of one half plane
// needs, each value as fft_2d makes it.
void fft_2d(std::vector<Complex>& image, int n, int low_columns, int high_columns);

}  // namespace umf
