// Tests of the field renderer and its PNG/zlib writer. Images are decoded by
// independent code (OpenCV's libpng, poppler's pdftoppm, a small inflater
// below) and compared module by module with the field.
#include <gtest/gtest.h>

#include <opencv2/core.hpp>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <map>
#include <random>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

#include "shared/field/field.hpp"
#include "shared/field/png_writer.hpp"
#include "shared/field/render.hpp"

namespace {

using umf::ImageFormat;
using umf::RenderOptions;
using umf::Rgb;

// ---- helpers ----

umf::Field random_field(int width, int height, int window, int colors, unsigned seed) {
    umf::Field f = umf::make_field(width, height, window, colors, umf::default_key(colors));
    std::mt19937 rng(seed);
    std::uniform_int_distribution<int> value(0, colors - 1);
    for (auto& m : f.modules) m = static_cast<std::uint8_t>(value(rng));
    return f;
}

Rgb parse_hex(const std::string& hex) {
    auto channel = [&](int at) { return static_cast<std::uint8_t>(std::stoi(hex.substr(at, 2), nullptr, 16)); };
    return {channel(1), channel(3), channel(5)};
}

std::vector<Rgb> palette_of(const umf::Field& f) {
    std::vector<Rgb> out;
    for (const auto& hex : f.palette.empty() ? umf::grey_palette(f.colors) : f.palette) out.push_back(parse_hex(hex));
    return out;
}

Rgb pixel(const cv::Mat& bgr, int x, int y) {
    cv::Vec3b v = bgr.at<cv::Vec3b>(y, x);
    return {v[2], v[1], v[0]};
}

std::string show(const Rgb& c) {
    return "(" + std::to_string(c[0]) + "," + std::to_string(c[1]) + "," + std::to_string(c[2]) + ")";
}

cv::Mat decode(const std::string& bytes) {
    std::vector<uchar> buf(bytes.begin(), bytes.end());
    return cv::imdecode(buf, cv::IMREAD_COLOR);
}

// Checks the centre pixel of every module and returns the number of mismatches,
// reporting the first few.
int check_module_centres(const cv::Mat& img, const umf::Field& f, int quiet, double px_per_module) {
    auto palette = palette_of(f);
    int bad = 0;
    for (int i = 0; i < f.height; ++i) {
        for (int j = 0; j < f.width; ++j) {
            int x = static_cast<int>(std::floor((quiet + j + 0.5) * px_per_module));
            int y = static_cast<int>(std::floor((quiet + i + 0.5) * px_per_module));
            Rgb want = palette[f.at(i, j)];
            Rgb got = pixel(img, x, y);
            if (got != want && ++bad <= 5)
                ADD_FAILURE() << "module (" << i << "," << j << ") at pixel (" << x << "," << y << ") is " << show(got)
                              << ", want " << show(want);
        }
    }
    return bad;
}

// PNG chunks by type, after checking the signature and every CRC.
std::multimap<std::string, std::string> png_chunks(const std::string& png) {
    std::multimap<std::string, std::string> chunks;
    EXPECT_EQ(png.substr(0, 8), std::string("\x89PNG\r\n\x1a\n", 8));
    std::size_t pos = 8;
    auto u32 = [&](std::size_t at) {
        return static_cast<std::uint32_t>(static_cast<unsigned char>(png[at])) << 24 |
               static_cast<std::uint32_t>(static_cast<unsigned char>(png[at + 1])) << 16 |
               static_cast<std::uint32_t>(static_cast<unsigned char>(png[at + 2])) << 8 |
               static_cast<std::uint32_t>(static_cast<unsigned char>(png[at + 3]));
    };
    while (pos + 12 <= png.size()) {
        std::uint32_t length = u32(pos);
        std::string type = png.substr(pos + 4, 4);
        std::string data = png.substr(pos + 8, length);
        EXPECT_EQ(u32(pos + 8 + length), umf::crc32(png.substr(pos + 4, 4 + length))) << "CRC of " << type;
        chunks.emplace(type, data);
        pos += 12 + length;
    }
    EXPECT_EQ(pos, png.size());
    return chunks;
}

std::string idat(const std::multimap<std::string, std::string>& chunks) {
    std::string z;
    auto [first, last] = chunks.equal_range("IDAT");
    for (auto it = first; it != last; ++it) z += it->second;
    return z;
}

std::uint32_t be32(const std::string& s, std::size_t at) {
    std::uint32_t v = 0;
    for (std::size_t i = 0; i < 4; ++i) v = v << 8 | static_cast<unsigned char>(s[at + i]);
    return v;
}

// A minimal inflater (stored and fixed-Huffman blocks, which is all the
// encoder emits), written from RFC 1950/1951 independently of the encoder.
class Inflater {
public:
    explicit Inflater(const std::string& z) : z_(z) {}

    std::string run() {
        if (z_.size() < 6) throw std::runtime_error("zlib stream too short");
        auto cmf = static_cast<unsigned char>(z_[0]), flg = static_cast<unsigned char>(z_[1]);
        if ((cmf & 0x0F) != 8 || (cmf * 256 + flg) % 31 != 0 || (flg & 0x20))
            throw std::runtime_error("bad zlib header");
        pos_ = 2;
        std::string out;
        bool final = false;
        while (!final) {
            final = bits(1);
            unsigned type = bits(2);
            if (type == 0) {
                align();
                std::size_t len = byte() | byte() << 8;
                std::size_t nlen = byte() | byte() << 8;
                if ((len ^ 0xFFFF) != nlen) throw std::runtime_error("bad stored length");
                for (std::size_t i = 0; i < len; ++i) out.push_back(static_cast<char>(byte()));
            } else if (type == 1) {
                fixed_block(out);
            } else {
                throw std::runtime_error("unexpected block type " + std::to_string(type));
            }
        }
        align();
        std::uint32_t adler = 0;
        for (int i = 0; i < 4; ++i) adler = adler << 8 | byte();
        if (pos_ != z_.size()) throw std::runtime_error("trailing bytes after the zlib stream");
        if (adler != reference_adler(out)) throw std::runtime_error("Adler-32 mismatch");
        return out;
    }

private:
    static std::uint32_t reference_adler(const std::string& s) {
        std::uint64_t a = 1, b = 0;
        for (unsigned char c : s) {
            a = (a + c) % 65521;
            b = (b + a) % 65521;
        }
        return static_cast<std::uint32_t>(b << 16 | a);
    }
    unsigned bit() {
        if (pos_ >= z_.size()) throw std::runtime_error("zlib stream ends early");
        unsigned v = (static_cast<unsigned char>(z_[pos_]) >> bit_) & 1;
        if (++bit_ == 8) {
            bit_ = 0;
            ++pos_;
        }
        return v;
    }
    unsigned bits(int n) {
        unsigned v = 0;
        for (int i = 0; i < n; ++i) v |= bit() << i;
        return v;
    }
    unsigned huffman(int n, unsigned start = 0) {
        unsigned v = start;
        for (int i = 0; i < n; ++i) v = v << 1 | bit();
        return v;
    }
    void align() {
        if (bit_ != 0) {
            bit_ = 0;
            ++pos_;
        }
    }
    unsigned byte() {
        if (pos_ >= z_.size()) throw std::runtime_error("zlib stream ends early");
        return static_cast<unsigned char>(z_[pos_++]);
    }
    unsigned symbol() {
        unsigned c = huffman(7);
        if (c <= 0x17) return 256 + c;
        c = huffman(1, c);
        if (c >= 0x30 && c <= 0xBF) return c - 0x30;
        if (c >= 0xC0 && c <= 0xC7) return 280 + c - 0xC0;
        c = huffman(1, c);
        return 144 + c - 0x190;
    }
    void fixed_block(std::string& out) {
        static const unsigned kLenBase[] = {3,  4,  5,  6,  7,  8,  9,  10, 11,  13,  15,  17,  19,  23, 27,
                                            31, 35, 43, 51, 59, 67, 83, 99, 115, 131, 163, 195, 227, 258};
        static const int kLenExtra[] = {0, 0, 0, 0, 0, 0, 0, 0, 1, 1, 1, 1, 2, 2, 2,
                                        2, 3, 3, 3, 3, 4, 4, 4, 4, 5, 5, 5, 5, 0};
        for (;;) {
            unsigned s = symbol();
            if (s < 256) {
                out.push_back(static_cast<char>(s));
                continue;
            }
            if (s == 256) return;
            if (s > 285) throw std::runtime_error("bad length symbol");
            std::size_t length = kLenBase[s - 257] + bits(kLenExtra[s - 257]);
            unsigned dcode = huffman(5);
            if (dcode > 29) throw std::runtime_error("bad distance code");
            // Distance bases follow from the extra-bit counts: 1,2,3,4,5,7,9,13,...
            std::size_t base = 1;
            for (unsigned c = 0; c < dcode; ++c) base += std::size_t{1} << (c < 2 ? 0 : c / 2 - 1);
            int extra = dcode < 2 ? 0 : static_cast<int>(dcode / 2 - 1);
            std::size_t distance = base + bits(extra);
            if (distance > out.size() || distance > 32768) throw std::runtime_error("distance too far back");
            for (std::size_t i = 0; i < length; ++i) out.push_back(out[out.size() - distance]);
        }
    }

    const std::string& z_;
    std::size_t pos_ = 0;
    int bit_ = 0;
};

std::filesystem::path temp_path(const std::string& name) {
    return std::filesystem::temp_directory_path() /
           ("umf_render_test_" + std::to_string(::testing::UnitTest::GetInstance()->random_seed()) + "_" + name);
}

// ---- checksums and zlib ----

TEST(Checksums, KnownValues) {
    EXPECT_EQ(umf::crc32("123456789"), 0xCBF43926u);
    EXPECT_EQ(umf::crc32(""), 0u);
    EXPECT_EQ(umf::crc32("6789", umf::crc32("12345")), 0xCBF43926u);  // continuing
    EXPECT_EQ(umf::adler32("Wikipedia"), 0x11E60398u);
    EXPECT_EQ(umf::adler32(""), 1u);
    std::string big(100000, '\xff');  // exercises the modulo blocking
    std::uint64_t a = 1, b = 0;
    for (unsigned char c : big) {
        a = (a + c) % 65521;
        b = (b + a) % 65521;
    }
    EXPECT_EQ(umf::adler32(big), static_cast<std::uint32_t>(b << 16 | a));
}

TEST(Zlib, RoundTripsVariedData) {
    std::mt19937 rng(7);
    std::vector<std::pair<std::string, std::string>> cases;
    cases.emplace_back("empty", "");
    cases.emplace_back("one byte", "x");
    cases.emplace_back("zeros", std::string(100000, '\0'));
    std::string random(20000, '\0');
    for (auto& c : random) c = static_cast<char>(rng() & 0xFF);
    cases.emplace_back("random", random);
    std::string rows;  // scanlines repeating with a period over the hash chain's comfort zone
    std::string row(3001, '\0');
    for (int r = 0; r < 40; ++r) {
        if (r % 7 == 0)
            for (auto& c : row) c = static_cast<char>(rng() % 3);
        rows += row;
    }
    cases.emplace_back("rows", rows);
    std::string far;  // a repeat more than 32 KiB back must not be referenced
    for (int i = 0; i < 5; ++i) far += random + std::string(40000 + i, 'a');
    cases.emplace_back("far repeats", far);
    for (const auto& [name, data] : cases) {
        for (std::size_t hint : {std::size_t{0}, std::size_t{3001}, std::size_t{40000}}) {
            std::string z = umf::zlib_compress(data, hint);
            std::string back;
            ASSERT_NO_THROW(back = Inflater(z).run()) << name << " hint " << hint;
            EXPECT_EQ(back, data) << name << " hint " << hint;
        }
    }
    EXPECT_LT(umf::zlib_compress(std::string(100000, '\0')).size(), 1000u);
    EXPECT_LT(umf::zlib_compress(rows, 3001).size(), rows.size() / 10);
}

// ---- PNG encoder ----

TEST(PngWriter, RgbRoundTrip) {
    const int w = 37, h = 23;
    std::mt19937 rng(3);
    std::vector<std::uint8_t> rgb(static_cast<std::size_t>(w) * h * 3);
    for (auto& c : rgb) c = static_cast<std::uint8_t>(rng() & 0xFF);
    for (int x = 0; x < w * 3; ++x) rgb[static_cast<std::size_t>(w) * 3 * 5 + x] = rgb[x];  // a repeated row
    std::string png = umf::encode_png_rgb(w, h, rgb, 300);
    auto chunks = png_chunks(png);
    ASSERT_EQ(chunks.count("pHYs"), 1u);
    EXPECT_EQ(be32(chunks.find("pHYs")->second, 0), 11811u);  // 300 dpi in pixels per metre
    cv::Mat img = decode(png);
    ASSERT_FALSE(img.empty());
    ASSERT_EQ(img.cols, w);
    ASSERT_EQ(img.rows, h);
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x) {
            std::size_t at = (static_cast<std::size_t>(y) * w + x) * 3;
            ASSERT_EQ(pixel(img, x, y), (Rgb{rgb[at], rgb[at + 1], rgb[at + 2]})) << x << "," << y;
        }
}

TEST(PngWriter, LargeImagesSpanSeveralIdatChunks) {
    const int w = 640, h = 600;  // random pixels do not compress: over 1 MiB of IDAT
    std::mt19937 rng(11);
    std::vector<std::uint8_t> rgb(static_cast<std::size_t>(w) * h * 3);
    for (auto& c : rgb) c = static_cast<std::uint8_t>(rng() & 0xFF);
    std::string png = umf::encode_png_rgb(w, h, rgb);
    auto chunks = png_chunks(png);
    EXPECT_GE(chunks.count("IDAT"), 2u);
    std::string raw = Inflater(idat(chunks)).run();
    ASSERT_EQ(raw.size(), static_cast<std::size_t>(h) * (w * 3 + 1));
    cv::Mat img = decode(png);
    ASSERT_EQ(img.cols, w);
    ASSERT_EQ(img.rows, h);
    cv::Mat want(h, w, CV_8UC3, rgb.data());
    cv::Mat want_bgr;
    cv::cvtColor(want, want_bgr, cv::COLOR_RGB2BGR);
    EXPECT_EQ(cv::norm(img, want_bgr, cv::NORM_INF), 0);
}

TEST(PngWriter, IndexedRoundTripAtEveryBitDepth) {
    const int w = 13, h = 9;  // 13 is odd for every pixels-per-byte, testing row padding
    for (std::size_t colours : {2u, 3u, 4u, 5u, 16u, 17u, 256u}) {
        std::vector<Rgb> palette;
        for (std::size_t i = 0; i < colours; ++i)
            palette.push_back(
                {static_cast<std::uint8_t>(i), static_cast<std::uint8_t>(255 - i), static_cast<std::uint8_t>(i * 7)});
        std::mt19937 rng(static_cast<unsigned>(colours));
        std::vector<std::uint8_t> idx(static_cast<std::size_t>(w) * h);
        for (auto& v : idx) v = static_cast<std::uint8_t>(rng() % colours);
        std::string png = umf::encode_png_indexed(w, h, palette, idx);
        auto chunks = png_chunks(png);
        const std::string& ihdr = chunks.find("IHDR")->second;
        int want_depth = colours <= 2 ? 1 : colours <= 4 ? 2 : colours <= 16 ? 4 : 8;
        EXPECT_EQ(static_cast<int>(ihdr[8]), want_depth) << colours << " colours";
        EXPECT_EQ(static_cast<int>(ihdr[9]), 3);
        EXPECT_EQ(chunks.find("PLTE")->second.size(), colours * 3);
        EXPECT_EQ(chunks.count("pHYs"), 0u);
        ASSERT_NO_THROW(Inflater(idat(chunks)).run());
        cv::Mat img = decode(png);
        ASSERT_EQ(img.cols, w);
        ASSERT_EQ(img.rows, h);
        for (int y = 0; y < h; ++y)
            for (int x = 0; x < w; ++x)
                ASSERT_EQ(pixel(img, x, y), palette[idx[static_cast<std::size_t>(y) * w + x]])
                    << colours << " colours at " << x << "," << y;
    }
}

TEST(PngWriter, RejectsInconsistentInput) {
    std::vector<Rgb> two = {Rgb{0, 0, 0}, Rgb{255, 255, 255}};
    EXPECT_THROW(umf::encode_png_indexed(2, 2, two, {0, 1, 2, 0}), std::invalid_argument);
    EXPECT_THROW(umf::encode_png_indexed(2, 2, two, {0, 1, 1}), std::invalid_argument);
    EXPECT_THROW(umf::encode_png_indexed(2, 2, {}, {0, 0, 0, 0}), std::invalid_argument);
    EXPECT_THROW(umf::encode_png_indexed(0, 2, two, {}), std::invalid_argument);
    EXPECT_THROW(umf::encode_png_rgb(2, 2, std::vector<std::uint8_t>(11)), std::invalid_argument);
}

// ---- format selection ----

TEST(ImageFormatForPath, UsesTheExtension) {
    EXPECT_EQ(umf::image_format_for_path("field.png"), ImageFormat::png);
    EXPECT_EQ(umf::image_format_for_path("/tmp/a.b/FIELD.SVG"), ImageFormat::svg);
    EXPECT_EQ(umf::image_format_for_path("out.Pdf"), ImageFormat::pdf);
    EXPECT_THROW(umf::image_format_for_path("field.jpg"), std::invalid_argument);
    EXPECT_THROW(umf::image_format_for_path("field"), std::invalid_argument);
    EXPECT_THROW(umf::image_format_for_path("dir.png/field"), std::invalid_argument);
    EXPECT_THROW(umf::image_format_for_path("field.png.bak"), std::invalid_argument);
    try {
        umf::image_format_for_path("shot.jpeg");
        FAIL() << "no exception";
    } catch (const std::invalid_argument& e) {
        EXPECT_NE(std::string(e.what()).find("shot.jpeg"), std::string::npos) << e.what();
    }
}

// ---- PNG rendering ----

umf::Field three_colour_field() {
    umf::Field f = random_field(14, 9, 3, 3, 42);
    f.palette = {"#d62728", "#1f77b4", "#ffdd57"};  // the last is the lightest by luma
    return f;
}

TEST(RenderPng, EveryPixelMatchesTheFieldWithQuietZone) {
    umf::Field f = three_colour_field();
    RenderOptions o;
    o.module_px = 7;
    o.quiet_zone = 2;
    cv::Mat img = decode(umf::render_field(f, ImageFormat::png, o));
    ASSERT_FALSE(img.empty());
    ASSERT_EQ(img.cols, (14 + 4) * 7);
    ASSERT_EQ(img.rows, (9 + 4) * 7);
    auto palette = palette_of(f);
    EXPECT_EQ(check_module_centres(img, f, 2, 7), 0);
    int bad = 0;
    for (int y = 0; y < img.rows; ++y)
        for (int x = 0; x < img.cols; ++x) {
            int i = y / 7 - 2, j = x / 7 - 2;
            bool inside = i >= 0 && i < f.height && j >= 0 && j < f.width;
            Rgb want = inside ? palette[f.at(i, j)] : palette[2];
            if (pixel(img, x, y) != want && ++bad <= 5) ADD_FAILURE() << "pixel " << x << "," << y;
        }
    EXPECT_EQ(bad, 0);
}

TEST(RenderPng, DefaultsToTenPixelsAndGreys) {
    umf::Field f = random_field(8, 6, 3, 2, 1);
    f.palette.clear();
    cv::Mat img = decode(umf::render_field(f, ImageFormat::png, {}));
    ASSERT_EQ(img.cols, 80);
    ASSERT_EQ(img.rows, 60);
    EXPECT_EQ(check_module_centres(img, f, 0, 10), 0);
    EXPECT_EQ(pixel(img, 5, 5), (f.at(0, 0) ? Rgb{255, 255, 255} : Rgb{0, 0, 0}));
}

TEST(RenderPng, TenColoursUseFourBitPixels) {
    umf::Field f = random_field(20, 11, 3, 10, 9);
    RenderOptions o;
    o.module_px = 3;
    o.quiet_zone = 1;
    std::string png = umf::render_field(f, ImageFormat::png, o);
    EXPECT_EQ(static_cast<int>(png_chunks(png).find("IHDR")->second[8]), 4);
    cv::Mat img = decode(png);
    ASSERT_EQ(img.cols, 22 * 3);
    EXPECT_EQ(check_module_centres(img, f, 1, 3), 0);
}

TEST(RenderPng, MillimetresAndDpiGiveThePixelSize) {
    umf::Field f = three_colour_field();
    RenderOptions o;
    o.module_mm = 2.54;  // a tenth of an inch: exactly 30 px at 300 dpi
    o.dpi = 300;
    o.quiet_zone = 1;
    o.module_px = 99;  // ignored: the physical size wins
    std::string png = umf::render_field(f, ImageFormat::png, o);
    cv::Mat img = decode(png);
    EXPECT_EQ(img.cols, 16 * 30);
    EXPECT_EQ(img.rows, 11 * 30);
    EXPECT_EQ(check_module_centres(img, f, 1, 30), 0);
    auto chunks = png_chunks(png);
    ASSERT_EQ(chunks.count("pHYs"), 1u);
    EXPECT_EQ(be32(chunks.find("pHYs")->second, 0), 11811u);

    // A fractional pixel count per module keeps the total size exact.
    o.module_mm = 1;
    o.dpi = 600;
    double scale = 600 / 25.4;  // 23.62 px
    img = decode(umf::render_field(f, ImageFormat::png, o));
    EXPECT_EQ(img.cols, std::lround(16 * scale));
    EXPECT_EQ(img.rows, std::lround(11 * scale));
    EXPECT_EQ(check_module_centres(img, f, 1, scale), 0);
}

TEST(RenderPng, CaptionAddsABandBelowAndLeavesTheFieldAlone) {
    umf::Field f = three_colour_field();
    RenderOptions o;
    o.module_px = 20;
    o.quiet_zone = 1;
    cv::Mat plain = decode(umf::render_field(f, ImageFormat::png, o));
    o.caption = "b3 (test) \xc3\xa9";
    cv::Mat captioned = decode(umf::render_field(f, ImageFormat::png, o));
    ASSERT_EQ(captioned.cols, plain.cols);
    ASSERT_GT(captioned.rows, plain.rows);
    EXPECT_EQ(cv::norm(captioned(cv::Rect(0, 0, plain.cols, plain.rows)), plain, cv::NORM_INF), 0);
    auto palette = palette_of(f);
    int ink = 0, other = 0;
    for (int y = plain.rows; y < captioned.rows; ++y)
        for (int x = 0; x < captioned.cols; ++x) {
            Rgb c = pixel(captioned, x, y);
            if (c == palette[0])
                ++ink;  // the darkest colour
            else if (c != palette[2])
                ++other;
        }
    EXPECT_GT(ink, 100);
    EXPECT_EQ(other, 0);
}

TEST(RenderPng, CompressesAFullHdBinaryField) {
    umf::Field f = random_field(64, 36, 4, 2, 2024);
    RenderOptions o;
    o.module_px = 30;
    std::string png = umf::render_field(f, ImageFormat::png, o);
    cv::Mat img = decode(png);
    ASSERT_EQ(img.cols, 1920);
    ASSERT_EQ(img.rows, 1080);
    EXPECT_EQ(check_module_centres(img, f, 0, 30), 0);
    EXPECT_LT(png.size(), 150u * 1024);
    RecordProperty("png_bytes", static_cast<int>(png.size()));
    std::printf("64x36 binary field at 30 px: %zu bytes\n", png.size());
}

// ---- option checking ----

void expect_invalid(const umf::Field& f, ImageFormat format, const RenderOptions& o, const std::string& mention) {
    try {
        umf::render_field(f, format, o);
        ADD_FAILURE() << "no exception, expected one mentioning '" << mention << "'";
    } catch (const std::invalid_argument& e) {
        EXPECT_NE(std::string(e.what()).find(mention), std::string::npos) << e.what();
    }
}

TEST(RenderField, RejectsBadOptions) {
    umf::Field f = three_colour_field();
    for (ImageFormat format : {ImageFormat::png, ImageFormat::svg, ImageFormat::pdf}) {
        RenderOptions o;
        o.module_px = -3;
        expect_invalid(f, format, o, "-3");
        o = {};
        o.module_mm = -0.5;
        expect_invalid(f, format, o, "-0.5");
        o = {};
        o.module_mm = std::nan("");
        expect_invalid(f, format, o, "module_mm");
        o.module_mm = 1e6;
        expect_invalid(f, format, o, "1000000");
        o = {};
        o.dpi = 0;
        expect_invalid(f, format, o, "dpi");
        o = {};
        o.quiet_zone = -1;
        expect_invalid(f, format, o, "-1");
        umf::Field broken = f;
        broken.modules[5] = 7;
        expect_invalid(broken, format, {}, "value 7");
    }
    RenderOptions o;
    o.module_px = 1000;  // 14000 x 9000 px: fine
    EXPECT_NO_THROW(umf::render_field(random_field(4, 4, 3, 2, 0), ImageFormat::svg, o));
    o.module_px = 1200;  // 16800 px wide
    expect_invalid(f, ImageFormat::png, o, "16800");
    o.module_px = 100;  // 16100 x 16100 px: within the side limit, over the pixel limit
    expect_invalid(random_field(161, 161, 4, 2, 0), ImageFormat::png, o, "256000000");
    o = {};
    o.module_mm = 0.05;  // 0.59 px at 300 dpi
    expect_invalid(f, ImageFormat::png, o, "0.05");
}

// ---- SVG ----

// The value of name="..." in one line of markup; empty when absent.
std::string attribute(const std::string& line, const std::string& name) {
    std::string key = " " + name + "=\"";
    std::size_t at = line.find(key);
    if (at == std::string::npos) return {};
    at += key.size();
    return line.substr(at, line.find('"', at) - at);
}

TEST(RenderSvg, RectanglesRebuildTheField) {
    umf::Field f = three_colour_field();
    RenderOptions o;
    o.quiet_zone = 3;
    o.module_mm = 2.5;
    std::string svg = umf::render_field(f, ImageFormat::svg, o);
    EXPECT_EQ(svg.rfind("<?xml", 0), 0u);
    EXPECT_NE(svg.find("shape-rendering=\"crispEdges\""), std::string::npos);
    EXPECT_NE(svg.find("width=\"50mm\" height=\"37.5mm\" viewBox=\"0 0 20 15\""), std::string::npos)
        << svg.substr(0, 300);

    // One background rectangle plus one per horizontal run not in the lightest colour.
    int runs = 0;
    for (int i = 0; i < f.height; ++i)
        for (int j = 0; j < f.width; ++j)
            if (f.at(i, j) != 2 && (j == 0 || f.at(i, j - 1) != f.at(i, j))) ++runs;
    auto palette = palette_of(f);
    std::vector<std::vector<Rgb>> grid(15, std::vector<Rgb>(20, Rgb{1, 2, 3}));
    Rgb current{};
    int rects = 0;
    std::istringstream lines(svg);
    for (std::string line; std::getline(lines, line);) {
        if (line.rfind("<g fill=\"", 0) == 0) {
            current = parse_hex(attribute(line, "fill"));
        } else if (line.rfind("<rect ", 0) == 0) {
            ++rects;
            std::string fill = attribute(line, "fill");
            Rgb colour = fill.empty() ? current : parse_hex(fill);
            int x = std::stoi(attribute(line, "x")), y = std::stoi(attribute(line, "y"));
            int w = std::stoi(attribute(line, "width")), h = std::stoi(attribute(line, "height"));
            for (int yy = y; yy < y + h; ++yy)
                for (int xx = x; xx < x + w; ++xx)
                    grid.at(static_cast<std::size_t>(yy)).at(static_cast<std::size_t>(xx)) = colour;
        } else {
            EXPECT_EQ(line.find("<rect"), std::string::npos) << "unparsed: " << line;
        }
    }
    EXPECT_EQ(rects, runs + 1);
    for (int y = 0; y < 15; ++y)
        for (int x = 0; x < 20; ++x) {
            int i = y - 3, j = x - 3;
            bool inside = i >= 0 && i < f.height && j >= 0 && j < f.width;
            EXPECT_EQ(grid[static_cast<std::size_t>(y)][static_cast<std::size_t>(x)],
                      inside ? palette[f.at(i, j)] : palette[2])
                << "module cell " << x << "," << y;
        }
}

TEST(RenderSvg, PixelUnitsAndEscapedCaption) {
    umf::Field f = three_colour_field();
    RenderOptions o;
    o.module_px = 12;
    o.caption = "a<b & \"c\" \xe2\x86\x92 \x01 \xff";
    std::string svg = umf::render_field(f, ImageFormat::svg, o);
    EXPECT_NE(svg.find("width=\"168\""), std::string::npos);
    EXPECT_NE(svg.find(">a&lt;b &amp; &quot;c&quot; \xe2\x86\x92   \xef\xbf\xbd</text>"), std::string::npos) << svg;
    EXPECT_EQ(svg.find("<b"), std::string::npos);
    EXPECT_EQ(svg.find('\x01'), std::string::npos);
    EXPECT_NE(svg.find("fill=\"#d62728\">a&lt;"), std::string::npos);  // the darkest colour
}

// ---- PDF ----

struct PdfStructure {
    std::vector<std::size_t> offsets;
    std::size_t startxref = 0;
};

PdfStructure check_pdf_structure(const std::string& pdf) {
    PdfStructure s;
    EXPECT_EQ(pdf.rfind("%PDF-1.4\n", 0), 0u);
    EXPECT_EQ(pdf.substr(pdf.size() - 6), "%%EOF\n");
    std::size_t sx = pdf.rfind("startxref\n");
    EXPECT_NE(sx, std::string::npos);
    s.startxref = std::stoul(pdf.substr(sx + 10));
    EXPECT_EQ(pdf.compare(s.startxref, 5, "xref\n"), 0);
    std::istringstream in(pdf.substr(s.startxref + 5));
    std::size_t first = 0, count = 0;
    in >> first >> count;
    EXPECT_EQ(first, 0u);
    std::size_t table = pdf.find('\n', s.startxref + 5) + 1;
    for (std::size_t n = 0; n < count; ++n) {
        std::string entry = pdf.substr(table + 20 * n, 20);
        EXPECT_EQ(entry.size(), 20u);
        EXPECT_EQ(entry.substr(18), " \n");
        if (n == 0) {
            EXPECT_EQ(entry, "0000000000 65535 f \n");
            continue;
        }
        std::size_t offset = std::stoul(entry.substr(0, 10));
        std::string header = std::to_string(n) + " 0 obj";
        EXPECT_EQ(pdf.compare(offset, header.size(), header), 0)
            << "xref entry " << n << " points at offset " << offset;
        s.offsets.push_back(offset);
    }
    EXPECT_NE(pdf.find("/Size " + std::to_string(count)), std::string::npos);
    return s;
}

std::string pdf_content(const std::string& pdf) {
    std::size_t dict = pdf.find("/FlateDecode");
    std::size_t len_at = pdf.rfind("/Length ", dict);
    std::size_t length = std::stoul(pdf.substr(len_at + 8));
    std::size_t start = pdf.find("stream\n", dict) + 7;
    EXPECT_EQ(pdf.compare(start + length, 10, "\nendstream"), 0);
    return Inflater(pdf.substr(start, length)).run();
}

TEST(RenderPdf, StructureAndContent) {
    umf::Field f = three_colour_field();
    RenderOptions o;
    o.module_mm = 25.4 / 72 * 5;  // 5 pt per module
    o.quiet_zone = 2;
    o.caption = "id (1) \\ \xc3\xa9";
    std::string pdf = umf::render_field(f, ImageFormat::pdf, o);
    PdfStructure s = check_pdf_structure(pdf);
    EXPECT_EQ(s.offsets.size(), 6u);
    EXPECT_NE(pdf.find("/MediaBox [0 0 90 "), std::string::npos);  // (14 + 4) modules * 5 pt
    std::string content = pdf_content(pdf);
    EXPECT_NE(content.find("(id \\(1\\) \\\\ ?) Tj"), std::string::npos) << content.substr(content.size() - 200);
    EXPECT_NE(content.find("5 0 0 -5 0 "), std::string::npos);
    int res = 0;
    for (std::size_t at = content.find(" re\n"); at != std::string::npos; at = content.find(" re\n", at + 1)) ++res;
    int runs = 0;
    for (int i = 0; i < f.height; ++i)
        for (int j = 0; j < f.width; ++j)
            if (f.at(i, j) != 2 && (j == 0 || f.at(i, j - 1) != f.at(i, j))) ++runs;
    EXPECT_EQ(res, runs);  // the background uses "re f" on one line
}

TEST(RenderPdf, RasterisedByPopplerMatchesTheField) {
    const char* tool = "/usr/bin/pdftoppm";
    if (!std::filesystem::exists(tool)) GTEST_SKIP() << tool << " is not installed";
    umf::Field f = three_colour_field();
    RenderOptions o;
    o.module_px = 10;  // 10 pt per module: 10 px at 72 dpi
    o.quiet_zone = 1;
    o.caption = "k3 field";
    std::string pdf = umf::render_field(f, ImageFormat::pdf, o);
    auto in = temp_path("field.pdf");
    auto out = temp_path("field");
    {
        std::ofstream file(in, std::ios::binary);
        file.write(pdf.data(), static_cast<std::streamsize>(pdf.size()));
    }
    std::string cmd = std::string(tool) + " -r 72 -png -singlefile '" + in.string() + "' '" + out.string() + "'";
    ASSERT_EQ(std::system(cmd.c_str()), 0) << cmd;
    cv::Mat img = cv::imread(out.string() + ".png", cv::IMREAD_COLOR);
    std::filesystem::remove(in);
    std::filesystem::remove(out.string() + ".png");
    ASSERT_FALSE(img.empty());
    EXPECT_EQ(img.cols, 16 * 10);
    EXPECT_GT(img.rows, 11 * 10);  // the caption band
    EXPECT_EQ(check_module_centres(img, f, 1, 10), 0);
    EXPECT_EQ(pixel(img, 4, 4), palette_of(f)[2]);  // quiet zone
}

}  // namespace
