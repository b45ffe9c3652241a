#include "shared/field/png_writer.hpp"

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <stdexcept>

namespace umf {

namespace {

constexpr std::array<std::uint32_t, 256> make_crc_table() {
    std::array<std::uint32_t, 256> table{};
    for (std::uint32_t n = 0; n < 256; ++n) {
        std::uint32_t c = n;
        for (int k = 0; k < 8; ++k) c = (c & 1) ? 0xEDB88320u ^ (c >> 1) : c >> 1;
        table[n] = c;
    }
    return table;
}

// ---- deflate (RFC 1951) with the fixed Huffman code ----

// Deflate packs bits starting at the least significant bit of each byte.
class BitWriter {
public:
    explicit BitWriter(std::string& out) : out_(out) {}

    void bits(std::uint32_t value, int count) {
        acc_ |= static_cast<std::uint64_t>(value) << fill_;
        fill_ += count;
        while (fill_ >= 8) {
            out_.push_back(static_cast<char>(acc_ & 0xFF));
            acc_ >>= 8;
            fill_ -= 8;
        }
    }

    // Huffman codes are defined most significant bit first, so they go out reversed.
    void code(std::uint32_t code, int length) {
        std::uint32_t reversed = 0;
        for (int i = 0; i < length; ++i) reversed |= ((code >> i) & 1u) << (length - 1 - i);
        bits(reversed, length);
    }

    void flush() {
        if (fill_ > 0) bits(0, 8 - fill_);
    }

private:
    std::string& out_;
    std::uint64_t acc_ = 0;
    int fill_ = 0;
};

constexpr std::array<std::uint16_t, 29> kLengthBase = {3,  4,  5,  6,  7,  8,  9,  10, 11,  13,  15,  17,  19,  23, 27,
                                                       31, 35, 43, 51, 59, 67, 83, 99, 115, 131, 163, 195, 227, 258};
constexpr std::array<std::uint8_t, 29> kLengthExtra = {0, 0, 0, 0, 0, 0, 0, 0, 1, 1, 1, 1, 2, 2, 2,
                                                       2, 3, 3, 3, 3, 4, 4, 4, 4, 5, 5, 5, 5, 0};
constexpr std::array<std::uint16_t, 30> kDistBase = {1,    2,    3,    4,    5,    7,    9,    13,    17,    25,
                                                     33,   49,   65,   97,   129,  193,  257,  385,   513,   769,
                                                     1025, 1537, 2049, 3073, 4097, 6145, 8193, 12289, 16385, 24577};
constexpr std::array<std::uint8_t, 30> kDistExtra = {0, 0, 0, 0, 1, 1, 2, 2,  3,  3,  4,  4,  5,  5,  6,
                                                     6, 7, 7, 8, 8, 9, 9, 10, 10, 11, 11, 12, 12, 13, 13};

constexpr std::size_t kMinMatch = 3;
constexpr std::size_t kMaxMatch = 258;
constexpr std::size_t kWindow = 32768;
constexpr int kHashBits = 15;
// Longer chains buy little on field images, whose repeats sit at the hinted distances.
constexpr int kMaxChain = 32;
constexpr std::size_t kNone = static_cast<std::size_t>(-1);

void put_symbol(BitWriter& out, unsigned symbol) {
    if (symbol < 144)
        out.code(0x30 + symbol, 8);
    else if (symbol < 256)
        out.code(0x190 + symbol - 144, 9);
    else if (symbol < 280)
        out.code(symbol - 256, 7);
    else
        out.code(0xC0 + symbol - 280, 8);
}

void put_match(BitWriter& out, std::size_t length, std::size_t distance) {
    std::size_t lc = kLengthBase.size() - 1;
    while (kLengthBase[lc] > length) --lc;
    put_symbol(out, static_cast<unsigned>(257 + lc));
    out.bits(static_cast<std::uint32_t>(length - kLengthBase[lc]), kLengthExtra[lc]);
    std::size_t dc = kDistBase.size() - 1;
    while (kDistBase[dc] > distance) --dc;
    out.code(static_cast<std::uint32_t>(dc), 5);
    out.bits(static_cast<std::uint32_t>(distance - kDistBase[dc]), kDistExtra[dc]);
}

// Remembers, for every 3-byte prefix hash, where it last occurred and, within
// the window, where it occurred before that.
class MatchFinder {
public:
    MatchFinder(std::string_view data, std::size_t hint)
        : data_(data), hint_(hint), head_(std::size_t{1} << kHashBits, kNone), prev_(kWindow, kNone) {}

    void insert(std::size_t pos) {
        if (pos + kMinMatch > data_.size()) return;
        std::size_t h = hash(pos);
        prev_[pos % kWindow] = head_[h];
        head_[h] = pos;
    }

    // Longest match at `pos` as {length, distance}; length 0 when none.
    std::pair<std::size_t, std::size_t> longest(std::size_t pos) const {
        std::size_t limit = std::min(kMaxMatch, data_.size() - pos);
        std::pair<std::size_t, std::size_t> best{0, 0};
        if (limit < kMinMatch) return best;
        auto consider = [&](std::size_t distance) {
            std::size_t n = 0;
            while (n < limit && data_[pos + n] == data_[pos + n - distance]) ++n;
            if (n > best.first) best = {n, distance};
        };
        for (std::size_t distance : {std::size_t{1}, hint_})
            if (distance > 0 && distance <= pos && distance <= kWindow) consider(distance);
        std::size_t candidate = head_[hash(pos)];
        for (int chain = 0; chain < kMaxChain && best.first < limit && candidate != kNone; ++chain) {
            if (pos - candidate > kWindow) break;
            consider(pos - candidate);
            candidate = prev_[candidate % kWindow];
        }
        if (best.first < kMinMatch) best = {0, 0};
        return best;
    }

private:
    std::size_t hash(std::size_t pos) const {
        auto byte = [&](std::size_t i) { return static_cast<std::uint32_t>(static_cast<unsigned char>(data_[i])); };
        std::uint32_t key = byte(pos) << 16 | byte(pos + 1) << 8 | byte(pos + 2);
        return (key * 2654435761u) >> (32 - kHashBits);
    }

    std::string_view data_;
    std::size_t hint_;
    std::vector<std::size_t> head_;
    std::vector<std::size_t> prev_;
};

// ---- PNG ----

void put_u32(std::string& out, std::uint32_t v) {
    for (int shift = 24; shift >= 0; shift -= 8) out.push_back(static_cast<char>((v >> shift) & 0xFF));
}

void put_chunk(std::string& png, std::string_view type, std::string_view data) {
    put_u32(png, static_cast<std::uint32_t>(data.size()));
    png.append(type);
    png.append(data);
    put_u32(png, crc32(data, crc32(type)));
}

// Prefixes every scanline with filter 0 (None) or 2 (Up), whichever has the
// smaller sum of absolute signed bytes: the usual heuristic, and it turns a
// row that repeats the one above into zeros.
std::string filter_scanlines(const std::vector<std::uint8_t>& raw, std::size_t rows, std::size_t stride) {
    std::string out;
    out.reserve(rows * (stride + 1));
    std::vector<std::uint8_t> up(stride);
    for (std::size_t y = 0; y < rows; ++y) {
        const std::uint8_t* row = raw.data() + y * stride;
        // The row above by its own pointer: row[i - stride] wraps the unsigned index.
        const std::uint8_t* above = y > 0 ? row - stride : nullptr;
        long cost_none = 0, cost_up = 0;
        for (std::size_t i = 0; i < stride; ++i) {
            up[i] = static_cast<std::uint8_t>(row[i] - (above ? above[i] : 0));
            cost_none += std::abs(static_cast<int>(static_cast<std::int8_t>(row[i])));
            cost_up += std::abs(static_cast<int>(static_cast<std::int8_t>(up[i])));
        }
        bool use_up = y > 0 && cost_up < cost_none;
        out.push_back(static_cast<char>(use_up ? 2 : 0));
        const std::uint8_t* src = use_up ? up.data() : row;
        out.append(reinterpret_cast<const char*>(src), stride);
    }
    return out;
}

void check_size(int w, int h, std::size_t bytes_per_pixel, std::size_t have, const char* what) {
    if (w < 1 || h < 1)
        throw std::invalid_argument("PNG size must be positive, not " + std::to_string(w) + " x " + std::to_string(h));
    // In 64 bits, so that no pair of int sizes can wrap around.
    std::uint64_t need = static_cast<std::uint64_t>(w) * static_cast<std::uint64_t>(h) * bytes_per_pixel;
    if (need != have)
        throw std::invalid_argument(std::string("PNG of ") + std::to_string(w) + " x " + std::to_string(h) + " needs " +
                                    std::to_string(need) + " " + what + " bytes, got " + std::to_string(have));
}

std::string assemble_png(int w, int h, int bit_depth, int color_type, std::string_view palette, double dpi,
                         std::string_view filtered, std::size_t stride) {
    std::string png("\x89PNG\r\n\x1a\n", 8);
    std::string ihdr;
    put_u32(ihdr, static_cast<std::uint32_t>(w));
    put_u32(ihdr, static_cast<std::uint32_t>(h));
    // Then compression 0 (deflate), filter method 0 (adaptive), no interlace.
    ihdr += {static_cast<char>(bit_depth), static_cast<char>(color_type), 0, 0, 0};
    put_chunk(png, "IHDR", ihdr);
    if (dpi > 0) {
        std::string phys;
        auto per_metre = static_cast<std::uint32_t>(std::lround(dpi / 0.0254));
        put_u32(phys, per_metre);
        put_u32(phys, per_metre);
        phys.push_back(1);  // unit: metre
        put_chunk(png, "pHYs", phys);
    }
    if (!palette.empty()) put_chunk(png, "PLTE", palette);
    // Several IDAT chunks rather than one lets streaming decoders start early
    // and keeps every chunk far below PNG's 2^31 byte limit.
    constexpr std::size_t kIdatChunk = std::size_t{1} << 20;
    std::string z = zlib_compress(filtered, stride + 1);
    for (std::size_t at = 0; at < z.size(); at += kIdatChunk)
        put_chunk(png, "IDAT", std::string_view(z).substr(at, kIdatChunk));
    put_chunk(png, "IEND", {});
    return png;
}

}  // namespace

std::uint32_t crc32(std::string_view data, std::uint32_t crc) {
    static constexpr auto table = make_crc_table();
    crc = ~crc;
    for (unsigned char c : data) crc = table[(crc ^ c) & 0xFF] ^ (crc >> 8);
    return ~crc;
}

std::uint32_t adler32(std::string_view data, std::uint32_t adler) {
    constexpr std::uint32_t kMod = 65521;
    // 5552 bytes is the most that can be summed before b may overflow 32 bits.
    constexpr std::size_t kBlock = 5552;
    std::uint32_t a = adler & 0xFFFF, b = adler >> 16;
    for (std::size_t start = 0; start < data.size(); start += kBlock) {
        std::size_t end = std::min(data.size(), start + kBlock);
        for (std::size_t i = start; i < end; ++i) {
            a += static_cast<unsigned char>(data[i]);
            b += a;
        }
        a %= kMod;
        b %= kMod;
    }
    return b << 16 | a;
}

std::string zlib_compress(std::string_view data, std::size_t row_length) {
    std::string out;
    out.reserve(64 + data.size() / 8);
    out += "\x78\x01";  // deflate, 32 KiB window, no dictionary; (0x78 << 8 | 0x01) % 31 == 0
    BitWriter bits(out);
    bits.bits(1, 1);  // final block
    bits.bits(1, 2);  // fixed Huffman codes
    MatchFinder finder(data, row_length);
    std::size_t pos = 0;
    while (pos < data.size()) {
        auto [length, distance] = finder.longest(pos);
        if (length == 0) {
            put_symbol(bits, static_cast<unsigned char>(data[pos]));
            length = 1;
        } else {
            put_match(bits, length, distance);
        }
        for (std::size_t end = pos + length; pos < end; ++pos) finder.insert(pos);
    }
    put_symbol(bits, 256);  // end of block
    bits.flush();
    put_u32(out, adler32(data));
    return out;
}

std::string encode_png_rgb(int w, int h, const std::vector<std::uint8_t>& rgb, double dpi) {
    check_size(w, h, 3, rgb.size(), "RGB");
    std::size_t stride = static_cast<std::size_t>(w) * 3;
    return assemble_png(w, h, 8, 2, {}, dpi, filter_scanlines(rgb, static_cast<std::size_t>(h), stride), stride);
}

std::string encode_png_indexed(int w, int h, const std::vector<Rgb>& palette, const std::vector<std::uint8_t>& indices,
                               double dpi) {
    if (palette.empty() || palette.size() > 256)
        throw std::invalid_argument("a PNG palette needs 1..256 entries, not " + std::to_string(palette.size()));
    check_size(w, h, 1, indices.size(), "index");
    for (std::size_t i = 0; i < indices.size(); ++i)
        if (indices[i] >= palette.size())
            throw std::invalid_argument("pixel " + std::to_string(i) + " has palette index " +
                                        std::to_string(indices[i]) + " but the palette has " +
                                        std::to_string(palette.size()) + " entries");
    int depth = palette.size() <= 2 ? 1 : palette.size() <= 4 ? 2 : palette.size() <= 16 ? 4 : 8;
    int per_byte = 8 / depth;
    std::size_t stride = (static_cast<std::size_t>(w) + per_byte - 1) / per_byte;
    std::vector<std::uint8_t> packed(stride * static_cast<std::size_t>(h), 0);
    for (std::size_t y = 0; y < static_cast<std::size_t>(h); ++y) {
        const std::uint8_t* src = indices.data() + y * static_cast<std::size_t>(w);
        std::uint8_t* dst = packed.data() + y * stride;
        for (int x = 0; x < w; ++x) {
            int shift = 8 - depth * (x % per_byte + 1);  // leftmost pixel in the high bits
            dst[x / per_byte] |= static_cast<std::uint8_t>(src[x] << shift);
        }
    }
    std::string plte;
    for (const Rgb& c : palette)
        plte.append({static_cast<char>(c[0]), static_cast<char>(c[1]), static_cast<char>(c[2])});
    return assemble_png(w, h, depth, 3, plte, dpi, filter_scanlines(packed, static_cast<std::size_t>(h), stride),
                        stride);
}

}  // namespace umf
