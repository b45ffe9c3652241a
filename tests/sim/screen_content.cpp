#include "tests/sim/screen_content.hpp"

#include <opencv2/imgproc.hpp>

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

namespace umf::sim {
namespace {

// cv::RNG rather than <random>: its sequence is fixed by OpenCV itself, so the
// screens are the same with every standard library.
using Rng = cv::RNG;

cv::Scalar bgr(int r, int g, int b) { return {double(b), double(g), double(r)}; }

// Braces, not parentheses: list-initialisation evaluates left to right, so
// the draws happen in the same order with every compiler.
cv::Scalar random_colour(Rng& rng) { return cv::Scalar{double(rng.uniform(0, 256)), double(rng.uniform(0, 256)), double(rng.uniform(0, 256))}; }

// Everything is laid out for a 1080-line screen and scaled by this.
double unit(cv::Size size) { return size.height / 1080.0; }

int px(double value, cv::Size size) { return std::max(1, static_cast<int>(std::lround(value * unit(size)))); }

std::string random_word(Rng& rng) {
    const int length = rng.uniform(2, 11);
    std::string word;
    for (int i = 0; i < length; ++i) word += static_cast<char>('a' + rng.uniform(0, 26));
    return word;
}

struct TextStyle {
    int font = cv::FONT_HERSHEY_SIMPLEX;
    double scale = 0.6;
    int thickness = 1;
    cv::Scalar colour;
};

int line_height(const TextStyle& style) {
    int baseline = 0;
    const cv::Size s = cv::getTextSize("Hg", style.font, style.scale, style.thickness, &baseline);
    return s.height + baseline;
}

// Random words from left until width is used up; returns the x where the
// text ended so callers can continue on the same line.
int draw_words(cv::Mat& img, Rng& rng, cv::Point at, int width, const TextStyle& style) {
    int x = at.x;
    int baseline = 0;
    const int space = cv::getTextSize(" ", style.font, style.scale, style.thickness, &baseline).width;
    while (true) {
        const std::string word = random_word(rng);
        const int w = cv::getTextSize(word, style.font, style.scale, style.thickness, &baseline).width;
        if (x + w > at.x + width) return x;
        cv::putText(img, word, {x, at.y}, style.font, style.scale, style.colour, style.thickness, cv::LINE_AA);
        x += w + space;
    }
}

// A paragraph of lines of words whose last line is short, as in real text.
int draw_paragraph(cv::Mat& img, Rng& rng, cv::Point at, int width, int lines, const TextStyle& style) {
    const int step = line_height(style) * 3 / 2;
    for (int i = 0; i < lines; ++i) {
        const int w = i + 1 == lines ? width * rng.uniform(30, 90) / 100 : width;
        draw_words(img, rng, {at.x, at.y + i * step}, w, style);
    }
    return at.y + lines * step;
}

cv::Mat gradient(cv::Size size, cv::Scalar from, cv::Scalar to, bool vertical) {
    cv::Mat out(size, CV_8UC3);
    const int n = vertical ? size.height : size.width;
    for (int i = 0; i < n; ++i) {
        const double t = n > 1 ? double(i) / (n - 1) : 0.0;
        const cv::Scalar c = from * (1 - t) + to * t;
        if (vertical)
            out.row(i).setTo(c);
        else
            out.col(i).setTo(c);
    }
    return out;
}

// Noise low-pass filtered at several scales, coarse scales stronger: the
// 1/f-like spectrum of natural images, which is what makes a photo busy at
// every viewing distance. Coarse octaves are made small and enlarged, because
// blurring at full size with sigmas of tens of pixels would be slow. Unit
// standard deviation per channel.
cv::Mat filtered_noise(cv::Size size, Rng& rng, double finest_sigma) {
    cv::Mat sum = cv::Mat::zeros(size, CV_32FC3);
    double weight = 1.0;
    for (int octave = 0, shrink = 1; octave < 6; ++octave, shrink *= 2, weight *= 1.7) {
        const cv::Size small{std::max(1, size.width / shrink), std::max(1, size.height / shrink)};
        cv::Mat noise(small, CV_32FC3);
        rng.fill(noise, cv::RNG::NORMAL, cv::Scalar::all(0), cv::Scalar::all(1));
        cv::GaussianBlur(noise, noise, {0, 0}, finest_sigma);
        noise *= weight * 2 * std::sqrt(CV_PI) * finest_sigma;  // undo the blur's loss of amplitude
        cv::Mat large;
        cv::resize(noise, large, size, 0, 0, cv::INTER_CUBIC);
        sum += large;
    }
    cv::Scalar mean, stddev;
    cv::meanStdDev(sum, mean, stddev);
    cv::Mat out;
    cv::transform(sum, out, cv::Matx34f(float(1 / stddev[0]), 0, 0, float(-mean[0] / stddev[0]),  //
                                        0, float(1 / stddev[1]), 0, float(-mean[1] / stddev[1]),  //
                                        0, 0, float(1 / stddev[2]), float(-mean[2] / stddev[2])));
    return out;
}

// A textured picture: a colour gradient with noise on top, as a stand-in
// for a photograph inside a page.
cv::Mat photo_patch(cv::Size size, Rng& rng) {
    const cv::Scalar a = random_colour(rng);
    const cv::Scalar b = random_colour(rng);
    const bool vertical = rng.uniform(0, 2) == 1;
    cv::Mat base;
    gradient(size, a, b, vertical).convertTo(base, CV_32FC3);
    const double finest = 1.0 + rng.uniform(0.0, 2.0);
    const cv::Mat noise = filtered_noise(size, rng, finest);
    const double contrast = rng.uniform(4.0, 12.0);
    cv::Mat out;
    cv::Mat(base + noise * (contrast * 3)).convertTo(out, CV_8UC3);
    return out;
}

// Pastes src into dst at rect, seen through an ellipse, so pictures have
// soft shapes and not only rectangles.
void paste_ellipse(cv::Mat& dst, const cv::Mat& src, cv::Rect rect) {
    rect &= cv::Rect({0, 0}, dst.size());
    if (rect.empty()) return;
    cv::Mat mask = cv::Mat::zeros(rect.size(), CV_8U);
    cv::ellipse(mask, {rect.width / 2, rect.height / 2}, {rect.width / 2, rect.height / 2}, 0, 0, 360, 255, cv::FILLED,
                cv::LINE_AA);
    src(cv::Rect({0, 0}, rect.size())).copyTo(dst(rect), mask);
}

void draw_table(cv::Mat& img, Rng& rng, cv::Rect area, int rows, int cols, const TextStyle& style) {
    const int row_h = area.height / rows;
    const int col_w = area.width / cols;
    cv::rectangle(img, {area.x, area.y, area.width, row_h}, bgr(225, 230, 240), cv::FILLED);
    for (int r = 0; r <= rows; ++r)
        cv::line(img, {area.x, area.y + r * row_h}, {area.x + cols * col_w, area.y + r * row_h}, style.colour, 1);
    for (int c = 0; c <= cols; ++c)
        cv::line(img, {area.x + c * col_w, area.y}, {area.x + c * col_w, area.y + rows * row_h}, style.colour, 1);
    for (int r = 0; r < rows; ++r)
        for (int c = 0; c < cols; ++c) {
            const cv::Point at(area.x + c * col_w + col_w / 10, area.y + r * row_h + row_h * 2 / 3);
            if (r > 0 && c > 0)
                cv::putText(img, std::to_string(rng.uniform(0, 100000)), at, style.font, style.scale, style.colour,
                            style.thickness, cv::LINE_AA);
            else
                draw_words(img, rng, at, col_w * 8 / 10, style);
        }
}

cv::Mat document(cv::Size size, Rng& rng) {
    cv::Mat img(size, CV_8UC3, cv::Scalar::all(255));
    const int margin = size.width / 8;
    const int width = size.width - 2 * margin;
    const TextStyle title{cv::FONT_HERSHEY_DUPLEX, 1.6 * unit(size), px(2, size), bgr(10, 10, 10)};
    const TextStyle heading{cv::FONT_HERSHEY_DUPLEX, 1.0 * unit(size), px(2, size), bgr(20, 40, 90)};
    const TextStyle body{cv::FONT_HERSHEY_COMPLEX, 0.55 * unit(size), 1, bgr(0, 0, 0)};
    const TextStyle small{cv::FONT_HERSHEY_SIMPLEX, 0.42 * unit(size), 1, bgr(60, 60, 60)};

    int y = px(90, size);
    draw_words(img, rng, {margin, y}, width * 7 / 10, title);
    y += px(60, size);
    bool table_done = false;
    while (y < size.height - px(80, size)) {
        draw_words(img, rng, {margin, y}, width / 2, heading);
        y += px(40, size);
        y = draw_paragraph(img, rng, {margin, y}, width, rng.uniform(3, 7), body) + px(16, size);
        if (!table_done && y > size.height / 3) {
            const cv::Rect area(margin, y, width * 3 / 4, px(180, size));
            draw_table(img, rng, area, 6, 4, small);
            y += area.height + px(40, size);
            table_done = true;
        }
    }
    return img;
}

cv::Mat code_dark(cv::Size size, Rng& rng) {
    cv::Mat img(size, CV_8UC3, bgr(30, 30, 30));
    const int sidebar = size.width / 7;
    const int status = px(24, size);
    cv::rectangle(img, {0, 0, sidebar, size.height}, bgr(37, 37, 38), cv::FILLED);
    cv::rectangle(img, {0, size.height - status, size.width, status}, bgr(0, 122, 204), cv::FILLED);

    const TextStyle tree{cv::FONT_HERSHEY_SIMPLEX, 0.45 * unit(size), 1, bgr(204, 204, 204)};
    const int tree_step = line_height(tree) * 2;
    for (int y = px(40, size); y < size.height - status; y += tree_step)
        draw_words(img, rng, {px(16, size) + px(14, size) * rng.uniform(0, 3), y}, sidebar / 2, tree);

    // Token colours of a common dark theme: keywords, types, strings, comments, plain.
    const cv::Scalar colours[] = {bgr(86, 156, 214), bgr(78, 201, 176), bgr(206, 145, 120), bgr(106, 153, 85),
                                  bgr(212, 212, 212)};
    TextStyle code{cv::FONT_HERSHEY_PLAIN, 1.15 * unit(size), 1, {}};
    const TextStyle number{cv::FONT_HERSHEY_PLAIN, 1.0 * unit(size), 1, bgr(133, 133, 133)};
    const int step = line_height(code) * 3 / 2;
    const int left = sidebar + px(60, size);
    int indent = 0;
    int line = 1;
    for (int y = px(30, size); y < size.height - status - step / 2; y += step, ++line) {
        cv::putText(img, std::to_string(line), {sidebar + px(10, size), y}, number.font, number.scale, number.colour,
                    1, cv::LINE_AA);
        if (rng.uniform(0, 8) == 0) continue;  // blank line
        indent = std::clamp(indent + rng.uniform(-1, 2), 0, 5);
        int x = left + indent * px(32, size);
        const int tokens = rng.uniform(1, 8);
        for (int t = 0; t < tokens && x < size.width - px(40, size); ++t) {
            code.colour = colours[rng.uniform(0, 5)];
            x = draw_words(img, rng, {x, y}, std::min(px(160, size), size.width - x), code);
        }
    }
    return img;
}

cv::Mat web_page(cv::Size size, Rng& rng) {
    cv::Mat img(size, CV_8UC3, bgr(246, 247, 249));
    const int header = px(70, size);
    gradient({size.width, header}, bgr(20, 60, 130), bgr(40, 110, 190), false).copyTo(img(cv::Rect(0, 0, size.width, header)));
    const TextStyle nav{cv::FONT_HERSHEY_DUPLEX, 0.7 * unit(size), 1, bgr(255, 255, 255)};
    for (int x = size.width / 3; x < size.width - px(150, size); x += px(150, size))
        draw_words(img, rng, {x, header * 3 / 5}, px(120, size), nav);

    // A hero picture across the page, then three columns of cards.
    const int margin = size.width / 12;
    const cv::Rect hero(margin, header + px(30, size), size.width - 2 * margin, size.height / 4);
    const cv::Scalar sky = random_colour(rng);
    const cv::Scalar ground = random_colour(rng);
    gradient(hero.size(), sky, ground, false).copyTo(img(hero));
    for (int i = 0; i < 4; ++i) {
        const cv::Size blob{rng.uniform(hero.height / 2, hero.height), rng.uniform(hero.height / 3, hero.height)};
        const cv::Point at{hero.x + rng.uniform(0, hero.width - blob.width), hero.y + rng.uniform(0, hero.height - blob.height)};
        paste_ellipse(img, photo_patch(blob, rng), {at, blob});
    }
    const TextStyle headline{cv::FONT_HERSHEY_DUPLEX, 1.4 * unit(size), px(2, size), bgr(255, 255, 255)};
    draw_words(img, rng, {hero.x + px(40, size), hero.y + hero.height - px(40, size)}, hero.width / 2, headline);

    const int gap = px(30, size);
    const int col_w = (hero.width - 2 * gap) / 3;
    const int top = hero.br().y + gap;
    const TextStyle title{cv::FONT_HERSHEY_DUPLEX, 0.75 * unit(size), 1, bgr(30, 30, 30)};
    const TextStyle body{cv::FONT_HERSHEY_SIMPLEX, 0.5 * unit(size), 1, bgr(70, 70, 70)};
    for (int c = 0; c < 3; ++c) {
        const int x = hero.x + c * (col_w + gap);
        const cv::Rect picture(x, top, col_w, size.height / 5);
        photo_patch(picture.size(), rng).copyTo(img(picture));
        int y = picture.br().y + px(40, size);
        draw_words(img, rng, {x, y}, col_w, title);
        draw_paragraph(img, rng, {x, y + px(35, size)}, col_w, (size.height - y - px(60, size)) / (line_height(body) * 3 / 2),
                       body);
    }
    return img;
}

cv::Mat photo(cv::Size size, Rng& rng) {
    cv::Mat base = filtered_noise(size, rng, 1.0);
    // Mix the three noise channels so colours are correlated, as in nature,
    // instead of rainbow speckle.
    const cv::Matx33f mix(0.6f, 0.3f, 0.1f, 0.3f, 0.5f, 0.2f, 0.1f, 0.3f, 0.6f);
    cv::transform(base, base, mix);
    cv::Mat img;
    base.convertTo(img, CV_8UC3, 45.0, 115.0);

    const int shapes = 40;
    for (int i = 0; i < shapes; ++i) {
        const cv::Scalar colour = random_colour(rng);
        const cv::Point centre{rng.uniform(0, size.width), rng.uniform(0, size.height)};
        const int r = rng.uniform(size.height / 40, size.height / 6);
        switch (rng.uniform(0, 3)) {
        case 0: {
            const cv::Size axes{r, rng.uniform(r / 3, r + 1)};
            const double angle = rng.uniform(0, 180);
            cv::ellipse(img, centre, axes, angle, 0, 360, colour, cv::FILLED, cv::LINE_AA);
            break;
        }
        case 1:
            paste_ellipse(img, photo_patch({2 * r, 2 * r}, rng), {centre.x - r, centre.y - r, 2 * r, 2 * r});
            break;
        default: {
            const cv::Point end = centre + cv::Point{rng.uniform(-3 * r, 3 * r), rng.uniform(-3 * r, 3 * r)};
            const int thickness = rng.uniform(1, std::max(2, r / 6));
            cv::line(img, centre, end, colour, thickness, cv::LINE_AA);
        }
        }
    }
    // Lens-like softness so edges are not all pixel-sharp.
    cv::GaussianBlur(img, img, {0, 0}, 0.7 * unit(size));
    return img;
}

// A spreadsheet: a header row and a column of row numbers, light rules
// around every cell, numbers right-aligned and labels left-aligned, a few
// filled cells. Its rules run with the screen's edges, as the field's lines
// do, at a spacing of their own (rows of 20-26 px, columns of 70-160 px at
// 1080 lines).
cv::Mat spreadsheet(cv::Size size, Rng& rng) {
    cv::Mat img(size, CV_8UC3, cv::Scalar::all(255));
    const int row_h = px(rng.uniform(20, 27), size), header = px(56, size), gutter = px(46, size);
    const cv::Scalar rule = bgr(212, 212, 212), ink = bgr(25, 25, 25);
    const TextStyle cell{cv::FONT_HERSHEY_SIMPLEX, 0.42 * unit(size), 1, ink};
    cv::rectangle(img, {0, 0, size.width, header + row_h}, bgr(238, 238, 238), cv::FILLED);
    cv::rectangle(img, {0, header, gutter, size.height - header}, bgr(238, 238, 238), cv::FILLED);
    std::vector<int> cols{gutter};
    while (cols.back() < size.width) cols.push_back(cols.back() + px(rng.uniform(70, 161), size));
    int baseline = 0;
    for (int y = header, r = 0; y + row_h <= size.height; y += row_h, ++r) {
        for (std::size_t c = 0; c + 1 < cols.size(); ++c) {
            const cv::Rect box(cols[c], y, cols[c + 1] - cols[c], row_h);
            if (r > 0 && rng.uniform(0, 40) == 0) cv::rectangle(img, box, bgr(255, 242, 200), cv::FILLED);
            if (r > 0 && rng.uniform(0, 10) < 3) continue;  // empty cells
            const bool label = r == 0 || c == 0;
            const std::string text =
                label ? random_word(rng)
                      : std::to_string(rng.uniform(0, 100000)) + (rng.uniform(0, 2) ? "." + std::to_string(rng.uniform(10, 100)) : "");
            const int w = cv::getTextSize(text, cell.font, cell.scale, cell.thickness, &baseline).width;
            const int x = label ? box.x + px(4, size) : box.x + box.width - w - px(4, size);
            cv::putText(img, text, {x, y + row_h - px(7, size)}, cell.font, cell.scale, ink, cell.thickness, cv::LINE_AA);
        }
        cv::putText(img, std::to_string(r + 1), {px(6, size), y + row_h - px(7, size)}, cell.font, cell.scale, ink,
                    cell.thickness, cv::LINE_AA);
        cv::line(img, {0, y}, {size.width, y}, rule, 1);
    }
    for (int x : cols) cv::line(img, {x, header}, {x, size.height}, rule, 1);
    return img;
}

}  // namespace

const char* to_string(ScreenKind kind) {
    switch (kind) {
    case ScreenKind::document: return "document";
    case ScreenKind::code_dark: return "code_dark";
    case ScreenKind::web_page: return "web_page";
    case ScreenKind::photo: return "photo";
    case ScreenKind::blank: return "blank";
    case ScreenKind::spreadsheet: return "spreadsheet";
    }
    return "?";
}

cv::Mat make_screen(ScreenKind kind, cv::Size size, std::uint64_t seed) {
    CV_Assert(size.width > 0 && size.height > 0);
    // Each kind gets its own stream so that one seed does not give related
    // layouts across kinds.
    Rng rng(seed * 0x9E3779B97F4A7C15ull + static_cast<std::uint64_t>(kind) + 1);
    switch (kind) {
    case ScreenKind::document: return document(size, rng);
    case ScreenKind::code_dark: return code_dark(size, rng);
    case ScreenKind::web_page: return web_page(size, rng);
    case ScreenKind::photo: return photo(size, rng);
    case ScreenKind::spreadsheet: return spreadsheet(size, rng);
    case ScreenKind::blank: break;
    }
    return cv::Mat(size, CV_8UC3, cv::Scalar::all(128));
}

}  // namespace umf::sim
