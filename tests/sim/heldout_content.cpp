#include "tests/sim/heldout_content.hpp"

#include <opencv2/imgproc.hpp>

#include <algorithm>
#include <cmath>
#include <string>

namespace umf::sim {
namespace {

cv::Scalar rgb(int r, int g, int b) { return {double(b), double(g), double(r)}; }

struct Layout {
    double unit;  // screen px per layout px (layout is for 1440 lines)
    int px(double v) const { return std::max(1, static_cast<int>(std::lround(v * unit))); }
};

std::string digits(cv::RNG& rng, int n) {
    std::string s;
    for (int i = 0; i < n; ++i) s += static_cast<char>('0' + rng.uniform(0, 10));
    if (n > 3 && rng.uniform(0, 2) == 0) s.insert(s.size() - 2, ".");
    return s;
}

std::string token(cv::RNG& rng) {
    static const char* const kWords[] = {"const", "auto", "return", "if", "for", "value", "frame", "edge", "grid",
                                         "int", "std::vector", "size", "push_back", "else", "x", "y", "count"};
    return kWords[rng.uniform(0, 17)];
}

void text(cv::Mat& img, const std::string& s, cv::Point at, double scale, cv::Scalar colour, int thickness = 1) {
    cv::putText(img, s, at, cv::FONT_HERSHEY_PLAIN, scale, colour, thickness, cv::LINE_AA);
}

cv::Mat spreadsheet(cv::Size size, cv::RNG& rng, const Layout& l) {
    cv::Mat img(size, CV_8UC3, rgb(255, 255, 255));
    const int ribbon = l.px(150), header = l.px(28), row_h = l.px(30), col_w = l.px(130), row_hdr = l.px(50);
    img(cv::Rect(0, 0, size.width, ribbon)).setTo(rgb(243, 242, 241));
    for (int i = 0; i < 14; ++i)
        cv::rectangle(img, cv::Rect(l.px(20 + 90 * i), l.px(40), l.px(60), l.px(60)), rgb(200, 200, 200), cv::FILLED);
    img(cv::Rect(0, ribbon, size.width, header)).setTo(rgb(230, 230, 230));
    img(cv::Rect(0, ribbon, row_hdr, size.height - ribbon)).setTo(rgb(230, 230, 230));
    const int highlighted = rng.uniform(2, 8);
    for (int c = 0; row_hdr + c * col_w < size.width; ++c) {
        const int x = row_hdr + c * col_w;
        text(img, std::string(1, static_cast<char>('A' + c % 26)), {x + col_w / 2, ribbon + header - l.px(8)}, 1.2 * l.unit,
             rgb(60, 60, 60));
        for (int r = 0; ribbon + header + r * row_h < size.height; ++r) {
            const int y = ribbon + header + r * row_h;
            if (c == highlighted) img(cv::Rect(x, y, col_w, row_h) & cv::Rect({}, size)).setTo(rgb(226, 239, 218));
            if (r % 9 == 0) img(cv::Rect(x, y, col_w, row_h) & cv::Rect({}, size)).setTo(rgb(221, 235, 247));
            if (rng.uniform(0, 10) < 7) text(img, digits(rng, rng.uniform(2, 8)), {x + l.px(8), y + row_h - l.px(9)}, 1.1 * l.unit, rgb(20, 20, 20));
        }
    }
    for (int x = row_hdr; x < size.width; x += col_w) cv::line(img, {x, ribbon}, {x, size.height}, rgb(212, 212, 212), 1);
    for (int y = ribbon + header; y < size.height; y += row_h) cv::line(img, {0, y}, {size.width, y}, rgb(212, 212, 212), 1);
    return img;
}

cv::Mat dark_editor(cv::Size size, cv::RNG& rng, const Layout& l) {
    cv::Mat img(size, CV_8UC3, rgb(30, 30, 30));
    const int bar = l.px(48), tree = l.px(360), tabs = l.px(44), line_h = l.px(27), minimap = l.px(120);
    img(cv::Rect(0, 0, bar, size.height)).setTo(rgb(51, 51, 51));
    img(cv::Rect(bar, 0, tree, size.height)).setTo(rgb(37, 37, 38));
    img(cv::Rect(bar + tree, 0, size.width - bar - tree, tabs)).setTo(rgb(45, 45, 45));
    for (int y = tabs + line_h; y < size.height; y += line_h) {
        text(img, token(rng) + "_" + token(rng), {bar + l.px(20 + 16 * rng.uniform(0, 4)), y}, 1.1 * l.unit, rgb(204, 204, 204));
    }
    static const cv::Scalar kSyntax[] = {rgb(86, 156, 214), rgb(206, 145, 120), rgb(78, 201, 176), rgb(220, 220, 170),
                                         rgb(106, 153, 85), rgb(212, 212, 212)};
    const int code_x = bar + tree + l.px(70), code_w = size.width - code_x - minimap - l.px(20);
    int n = 1;
    for (int y = tabs + line_h; y < size.height; y += line_h, ++n) {
        text(img, std::to_string(n), {bar + tree + l.px(10), y}, 1.1 * l.unit, rgb(133, 133, 133));
        int x = code_x + l.px(28) * rng.uniform(0, 5);
        while (rng.uniform(0, 8) != 0) {
            const std::string t = token(rng);
            int base = 0;
            const int w = cv::getTextSize(t, cv::FONT_HERSHEY_PLAIN, 1.3 * l.unit, 1, &base).width;
            if (x + w > code_x + code_w) break;
            text(img, t, {x, y}, 1.3 * l.unit, kSyntax[rng.uniform(0, 6)]);
            x += w + l.px(10);
        }
        const int mm_w = rng.uniform(10, 90) * minimap / 100;
        cv::line(img, {size.width - minimap, y}, {size.width - minimap + mm_w, y}, rgb(90, 90, 90), std::max(1, l.px(3)));
    }
    return img;
}

cv::Mat video_frame(cv::Size size, cv::RNG& rng, const Layout& l) {
    cv::Mat img(size, CV_8UC3, cv::Scalar::all(0));
    const int bars = size.height / 8, controls = l.px(60);
    const cv::Rect picture(0, bars, size.width, size.height - 2 * bars);
    cv::Mat pic(picture.size(), CV_8UC3);
    // A dusk street: a warm gradient sky, soft blobs of light and dark shapes.
    for (int y = 0; y < pic.rows; ++y) {
        const double t = double(y) / pic.rows;
        pic.row(y).setTo(rgb(int(200 - 150 * t), int(120 - 80 * t), int(90 - 50 * t)));
    }
    for (int i = 0; i < 25; ++i) {
        const cv::Point c(rng.uniform(0, pic.cols), rng.uniform(pic.rows / 3, pic.rows));
        const int r = rng.uniform(pic.rows / 20, pic.rows / 4);
        cv::circle(pic, c, r, cv::Scalar{double(rng.uniform(0, 120)), double(rng.uniform(0, 100)), double(rng.uniform(20, 140))}, cv::FILLED);
    }
    for (int i = 0; i < 12; ++i)
        cv::circle(pic, {rng.uniform(0, pic.cols), rng.uniform(0, pic.rows)}, rng.uniform(4, 16) * pic.rows / 400, rgb(255, 230, 170), cv::FILLED);
    cv::GaussianBlur(pic, pic, {0, 0}, std::max(1.0, pic.rows / 120.0));
    pic.copyTo(img(picture));
    cv::rectangle(img, cv::Rect(0, size.height - bars - controls, size.width, controls), rgb(20, 20, 20), cv::FILLED);
    const int progress = size.width * rng.uniform(10, 90) / 100;
    cv::line(img, {l.px(20), size.height - bars - controls / 2}, {progress, size.height - bars - controls / 2}, rgb(230, 30, 30), l.px(5));
    return img;
}

cv::Mat landscape(cv::Size size, cv::RNG& rng, const Layout&) {
    cv::Mat img(size, CV_8UC3);
    const int horizon = size.height * rng.uniform(35, 55) / 100;
    for (int y = 0; y < size.height; ++y) {
        const double t = double(y) / size.height;
        img.row(y).setTo(y < horizon ? rgb(int(90 + 120 * t), int(150 + 80 * t), 235) : rgb(70, int(110 - 40 * t), 40));
    }
    // Hills: sums of sines as ridge lines, darker towards the front.
    for (int layer = 0; layer < 4; ++layer) {
        const double f1 = rng.uniform(1.0, 3.0), f2 = rng.uniform(4.0, 9.0), p1 = rng.uniform(0.0, 6.3), p2 = rng.uniform(0.0, 6.3);
        const int base = horizon + layer * size.height / 14;
        const cv::Scalar colour = rgb(60 + 20 * (3 - layer), 100 + 20 * (3 - layer) - 10 * layer, 60 + 25 * (3 - layer));
        for (int x = 0; x < size.width; ++x) {
            const double u = double(x) / size.width * 2 * CV_PI;
            const int top = base - static_cast<int>(size.height * (0.06 * std::sin(f1 * u + p1) + 0.02 * std::sin(f2 * u + p2) + 0.05));
            cv::line(img, {x, std::max(0, top)}, {x, size.height - 1}, colour);
        }
    }
    // Foliage texture in the foreground, clouds in the sky.
    cv::Mat noise(size, CV_8UC3);
    rng.fill(noise, cv::RNG::UNIFORM, 0, 40);
    cv::Mat fg = img(cv::Rect(0, horizon, size.width, size.height - horizon));
    cv::Mat n = noise(cv::Rect(0, horizon, size.width, size.height - horizon));
    cv::subtract(fg, n, fg);
    for (int i = 0; i < 8; ++i)
        cv::ellipse(img, {rng.uniform(0, size.width), rng.uniform(0, std::max(1, horizon / 2))},
                    {rng.uniform(size.width / 20, size.width / 8), rng.uniform(size.height / 60, size.height / 25)}, 0, 0, 360,
                    rgb(245, 245, 250), cv::FILLED, cv::LINE_AA);
    cv::GaussianBlur(img, img, {0, 0}, 1.2);
    return img;
}

cv::Mat board_tiles(cv::Size size, cv::RNG& rng, const Layout& l) {
    cv::Mat img(size, CV_8UC3, rgb(0, 121, 191));
    static const cv::Scalar kLabels[] = {rgb(97, 189, 79), rgb(242, 214, 0), rgb(255, 159, 26), rgb(235, 90, 70),
                                         rgb(195, 119, 224), rgb(0, 194, 224)};
    const int top = l.px(90), col_w = l.px(300), gap = l.px(14);
    img(cv::Rect(0, 0, size.width, l.px(50))).setTo(rgb(2, 106, 167));
    for (int x = gap; x + col_w < size.width; x += col_w + gap) {
        int y = top;
        const int bottom = size.height * rng.uniform(55, 98) / 100;
        cv::rectangle(img, cv::Rect(x, top, col_w, bottom - top), rgb(235, 236, 240), cv::FILLED);
        text(img, token(rng), {x + l.px(12), top + l.px(30)}, 1.4 * l.unit, rgb(23, 43, 77), 2);
        y += l.px(48);
        while (true) {
            const int h = l.px(60 + 20 * rng.uniform(0, 5));
            if (y + h > bottom - l.px(10)) break;
            const cv::Rect card(x + l.px(8), y, col_w - l.px(16), h);
            cv::rectangle(img, card, rgb(255, 255, 255), cv::FILLED);
            cv::rectangle(img, cv::Rect(card.x + l.px(8), card.y + l.px(8), l.px(40), l.px(8)), kLabels[rng.uniform(0, 6)], cv::FILLED);
            text(img, token(rng) + " " + token(rng), {card.x + l.px(8), card.y + l.px(40)}, 1.1 * l.unit, rgb(23, 43, 77));
            y += h + l.px(8);
        }
    }
    return img;
}

}  // namespace

const char* to_string(HeldoutContent content) {
    switch (content) {
    case HeldoutContent::spreadsheet: return "spreadsheet";
    case HeldoutContent::dark_editor: return "dark_editor";
    case HeldoutContent::video_frame: return "video_frame";
    case HeldoutContent::landscape: return "landscape";
    case HeldoutContent::board_tiles: return "board_tiles";
    }
    return "?";
}

cv::Mat make_heldout_screen(HeldoutContent content, cv::Size size, std::uint64_t seed) {
    cv::RNG rng(seed * 0xA24BAED4963EE407ull + static_cast<std::uint64_t>(content) * 0x9FB21C651E98DF25ull + 17);
    const Layout l{size.height / 1440.0};
    switch (content) {
    case HeldoutContent::spreadsheet: return spreadsheet(size, rng, l);
    case HeldoutContent::dark_editor: return dark_editor(size, rng, l);
    case HeldoutContent::video_frame: return video_frame(size, rng, l);
    case HeldoutContent::landscape: return landscape(size, rng, l);
    case HeldoutContent::board_tiles: return board_tiles(size, rng, l);
    }
    return {};
}

}  // namespace umf::sim
