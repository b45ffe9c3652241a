// A self-contained PNG encoder with its own zlib stream, so the core library
// needs nothing beyond the standard library (it must also build with
// emscripten, where linking zlib or libpng is a nuisance).
//
// The deflate stream uses the fixed Huffman codes and LZ77 matches found via a
// hash chain, seeded with the two distances that matter most for rendered
// fields: 1 (runs of equal bytes) and one scanline (rows repeated inside a
// module row). Without dynamic Huffman tables the output is about 1.5 to 2
// times what zlib -9 makes of a field image, which is still only a few KB for
// a Full HD field: marker fields are large blocks of equal pixels.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

namespace umf {

// CRC-32 as used by PNG chunks (and gzip), over `data`, continuing from `crc`.
std::uint32_t crc32(std::string_view data, std::uint32_t crc = 0);

// Adler-32 as used by the zlib stream trailer.
std::uint32_t adler32(std::string_view data, std::uint32_t adler = 1);

// A complete zlib stream (RFC 1950 header, one fixed-Huffman deflate block of
// RFC 1951, Adler-32 trailer). `row_length`, when non-zero, is the distance at
// which repeats are most likely (a PNG scanline including its filter byte);
// it is tried before the hash chain.
std::string zlib_compress(std::string_view data, std::size_t row_length = 0);

using Rgb = std::array<std::uint8_t, 3>;

// An 8-bit RGB PNG of w x h pixels; `rgb` holds 3 * w * h bytes, row-major,
// top row first. When dpi > 0 a pHYs chunk records it so that printing
// software reproduces the intended physical size. Throws std::invalid_argument
// on sizes that do not match.
std::string encode_png_rgb(int w, int h, const std::vector<std::uint8_t>& rgb, double dpi = 0);

// A palette PNG: `indices` holds w * h palette indices. The bit depth is the
// smallest of 1/2/4/8 that can hold palette.size() - 1, which makes a binary
// field 1 bit per pixel before compression. Throws std::invalid_argument for
// an empty palette, more than 256 entries, sizes that do not match or an index
// outside the palette.
std::string encode_png_indexed(int w, int h, const std::vector<Rgb>& palette, const std::vector<std::uint8_t>& indices,
                               double dpi = 0);

}  // namespace umf
