#include "tests/bench/plot.hpp"

#include <opencv2/imgproc.hpp>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <vector>

namespace umf::bench::plot {
namespace {

constexpr int kFont = cv::FONT_HERSHEY_SIMPLEX;
constexpr double kTextScale = 0.5;
constexpr double kTitleScale = 0.7;
const cv::Scalar kInk(30, 30, 30);
const cv::Scalar kGridInk(225, 225, 225);

// Room around the plot area for ticks and labels, and to the right for the
// legend, so it never hides data.
struct Frame {
    cv::Rect area;
    double x0 = 0, x1 = 1, y0 = 0, y1 = 1;
    int px(double x) const { return area.x + cvRound((x - x0) / (x1 - x0) * area.width); }
    int py(double y) const { return area.y + area.height - cvRound((y - y0) / (y1 - y0) * area.height); }
};

cv::Rect plot_area(cv::Size size) { return {80, 60, size.width - 80 - 250, size.height - 60 - 70}; }

// Round steps (1, 2, 5 times a power of ten) giving about `count` ticks.
double tick_step(double lo, double hi, int count) {
    const double raw = (hi - lo) / std::max(1, count);
    if (!(raw > 0)) return 1;
    const double p = std::pow(10.0, std::floor(std::log10(raw)));
    for (double m : {1.0, 2.0, 5.0})
        if (raw <= m * p) return m * p;
    return 10 * p;
}

std::string tick_text(double v, double step) {
    char buf[32];
    const int decimals = step >= 1 ? 0 : static_cast<int>(std::ceil(-std::log10(step) - 1e-9));
    // Sums of steps leave tiny residues around zero that print as "-0".
    std::snprintf(buf, sizeof buf, "%.*f", decimals, std::abs(v) < 1e-6 * step ? 0.0 : v);
    return buf;
}

void text(cv::Mat& img, const std::string& s, cv::Point at, double scale = kTextScale, int align = 0,
          const cv::Scalar& ink = kInk) {
    int base = 0;
    const cv::Size sz = cv::getTextSize(s, kFont, scale, 1, &base);
    // align: 0 left, 1 centre, 2 right; `at` is the baseline.
    const int dx = align == 1 ? -sz.width / 2 : (align == 2 ? -sz.width : 0);
    cv::putText(img, s, at + cv::Point(dx, 0), kFont, scale, ink, scale > kTextScale ? 2 : 1, cv::LINE_AA);
}

// putText draws horizontally only: draw into a strip and turn it.
void vertical_text(cv::Mat& img, const std::string& s, cv::Point centre) {
    int base = 0;
    const cv::Size sz = cv::getTextSize(s, kFont, kTextScale, 1, &base);
    cv::Mat strip(sz.height + base + 4, sz.width + 4, CV_8UC3, cv::Scalar::all(255));
    cv::putText(strip, s, {2, sz.height + 2}, kFont, kTextScale, kInk, 1, cv::LINE_AA);
    cv::rotate(strip, strip, cv::ROTATE_90_COUNTERCLOCKWISE);
    const cv::Rect at(centre.x - strip.cols / 2, centre.y - strip.rows / 2, strip.cols, strip.rows);
    const cv::Rect clipped = at & cv::Rect(0, 0, img.cols, img.rows);
    strip(clipped - at.tl()).copyTo(img(clipped));
}

void frame_and_labels(cv::Mat& img, const Frame& f, const Axes& axes) {
    text(img, axes.title, {f.area.x + f.area.width / 2, 35}, kTitleScale, 1);
    // Horizontal grid and y ticks.
    const double ys = tick_step(f.y0, f.y1, 6);
    for (double y = std::ceil(f.y0 / ys - 1e-9) * ys; y <= f.y1 + 1e-9 * ys; y += ys) {
        const int py = f.py(y);
        cv::line(img, {f.area.x, py}, {f.area.br().x, py}, kGridInk, 1);
        cv::line(img, {f.area.x - 5, py}, {f.area.x, py}, kInk, 1);
        text(img, tick_text(y, ys), {f.area.x - 8, py + 5}, kTextScale, 2);
    }
    cv::rectangle(img, f.area, kInk, 1);
    text(img, axes.x_label, {f.area.x + f.area.width / 2, img.rows - 20}, kTextScale, 1);
    vertical_text(img, axes.y_label, {22, f.area.y + f.area.height / 2});
}

void dashed_line(cv::Mat& img, cv::Point a, cv::Point b, const cv::Scalar& ink, int thickness, double on = 10,
                 double off = 6) {
    const double len = std::hypot(b.x - a.x, b.y - a.y);
    for (double s = 0; s < len; s += on + off) {
        const double e = std::min(len, s + on);
        const cv::Point2d d = cv::Point2d(b - a) / std::max(len, 1e-9);
        cv::line(img, cv::Point2d(a) + d * s, cv::Point2d(a) + d * e, ink, thickness, cv::LINE_AA);
    }
}

void styled_line(cv::Mat& img, cv::Point a, cv::Point b, const Series& s) {
    if (s.dotted)
        dashed_line(img, a, b, s.colour, 2, 3, 4);
    else if (s.dashed)
        dashed_line(img, a, b, s.colour, 2);
    else
        cv::line(img, a, b, s.colour, 2, cv::LINE_AA);
}

void marker(cv::Mat& img, cv::Point at, const Series& s) {
    const cv::Scalar& ink = s.colour;
    if (s.triangle_markers) {
        const std::vector<cv::Point> tri = {at + cv::Point(0, -6), at + cv::Point(6, 5), at + cv::Point(-6, 5)};
        cv::fillConvexPoly(img, tri, ink, cv::LINE_AA);
    } else if (s.square_markers)
        cv::rectangle(img, at - cv::Point(4, 4), at + cv::Point(4, 4), ink, cv::FILLED, cv::LINE_AA);
    else
        cv::circle(img, at, 5, ink, cv::FILLED, cv::LINE_AA);
}

void legend(cv::Mat& img, const Frame& f, const std::vector<Series>& series) {
    const int x = f.area.br().x + 20;
    int y = f.area.y + 10;
    for (const auto& s : series) {
        const cv::Point a(x, y), b(x + 36, y);
        styled_line(img, a, b, s);
        marker(img, (a + b) / 2, s);
        text(img, s.label, {x + 46, y + 5});
        y += 24;
    }
}

std::pair<double, double> padded(double lo, double hi) {
    if (!(hi > lo)) return {lo - 1, hi + 1};
    const double pad = 0.05 * (hi - lo);
    return {lo - pad, hi + pad};
}

}  // namespace

cv::Scalar colour(int index) {
    static const cv::Scalar kColours[] = {{180, 119, 31}, {14, 127, 255}, {44, 160, 44},  {40, 39, 214},
                                          {189, 103, 148}, {75, 86, 140}, {194, 119, 227}, {127, 127, 127}};
    return kColours[static_cast<std::size_t>(index) % std::size(kColours)];
}

cv::Mat line_chart(const Axes& axes, const std::vector<Series>& series, cv::Size size) {
    cv::Mat img(size, CV_8UC3, cv::Scalar::all(255));
    Frame f;
    f.area = plot_area(size);
    double xlo = INFINITY, xhi = -INFINITY, ylo = INFINITY, yhi = -INFINITY;
    for (const auto& s : series)
        for (std::size_t i = 0; i < s.x.size() && i < s.y.size(); ++i) {
            if (!std::isfinite(s.y[i])) continue;
            xlo = std::min(xlo, s.x[i]), xhi = std::max(xhi, s.x[i]);
            ylo = std::min(ylo, s.y[i]), yhi = std::max(yhi, s.y[i]);
        }
    if (!std::isfinite(xlo)) xlo = 0, xhi = 1, ylo = 0, yhi = 1;
    std::tie(f.x0, f.x1) = padded(xlo, xhi);
    std::tie(f.y0, f.y1) = axes.y_range ? *axes.y_range : padded(ylo, yhi);
    frame_and_labels(img, f, axes);

    // x ticks at the data's x values when there are few (opacities), else round steps.
    std::vector<double> xs;
    for (const auto& s : series) xs.insert(xs.end(), s.x.begin(), s.x.end());
    std::sort(xs.begin(), xs.end());
    xs.erase(std::unique(xs.begin(), xs.end()), xs.end());
    const double xstep = tick_step(f.x0, f.x1, 8);
    if (xs.size() > 10) {
        xs.clear();
        for (double x = std::ceil(f.x0 / xstep) * xstep; x <= f.x1; x += xstep) xs.push_back(x);
    }
    for (double x : xs) {
        const int px = f.px(x);
        cv::line(img, {px, f.area.br().y}, {px, f.area.br().y + 5}, kInk, 1);
        char buf[32];
        std::snprintf(buf, sizeof buf, "%g", x);
        text(img, buf, {px, f.area.br().y + 22}, kTextScale, 1);
    }

    cv::Mat plot = img(f.area);  // clip lines to the plot area
    const cv::Point off = f.area.tl();
    for (const auto& s : series) {
        std::optional<cv::Point> prev;
        for (std::size_t i = 0; i < s.x.size() && i < s.y.size(); ++i) {
            if (!std::isfinite(s.y[i])) {
                prev.reset();
                continue;
            }
            const cv::Point p(f.px(s.x[i]), f.py(s.y[i]));
            if (prev) styled_line(plot, *prev - off, p - off, s);
            marker(plot, p - off, s);
            prev = p;
        }
    }
    legend(img, f, series);
    return img;
}

cv::Mat bar_chart(const Axes& axes, const Bars& bars, cv::Size size) {
    cv::Mat img(size, CV_8UC3, cv::Scalar::all(255));
    Frame f;
    f.area = plot_area(size);
    double hi = 0;
    for (const auto& row : bars.values)
        for (double v : row)
            if (std::isfinite(v)) hi = std::max(hi, v);
    f.x0 = 0;
    f.x1 = 1;
    f.y0 = 0;
    f.y1 = hi > 0 ? hi * 1.12 : 1;
    if (axes.y_range) std::tie(f.y0, f.y1) = *axes.y_range;
    frame_and_labels(img, f, axes);

    const int groups = static_cast<int>(bars.groups.size()), per = static_cast<int>(bars.series.size());
    if (groups == 0 || per == 0) return img;
    const double group_w = static_cast<double>(f.area.width) / groups;
    const double bar_w = group_w * 0.75 / per;
    for (int g = 0; g < groups; ++g) {
        const double left = f.area.x + g * group_w + group_w * 0.125;
        text(img, bars.groups[static_cast<std::size_t>(g)], {cvRound(f.area.x + (g + 0.5) * group_w), f.area.br().y + 22},
             kTextScale, 1);
        for (int s = 0; s < per; ++s) {
            const auto& row = bars.values[static_cast<std::size_t>(s)];
            const double v = static_cast<std::size_t>(g) < row.size() ? row[static_cast<std::size_t>(g)] : NAN;
            if (!std::isfinite(v)) continue;
            const cv::Point tl(cvRound(left + s * bar_w + 2), std::max(f.area.y, f.py(v)));
            const cv::Point br(cvRound(left + (s + 1) * bar_w - 2), f.area.br().y);
            cv::rectangle(img, tl, br, bars.colours[static_cast<std::size_t>(s)], cv::FILLED);
            char buf[32];
            std::snprintf(buf, sizeof buf, v >= 100 ? "%.0f" : "%.1f", v);
            text(img, buf, {(tl.x + br.x) / 2, tl.y - 6}, kTextScale, 1);
        }
    }
    std::vector<Series> keys;
    for (int s = 0; s < per; ++s) {
        Series k;
        k.label = bars.series[static_cast<std::size_t>(s)];
        k.colour = bars.colours[static_cast<std::size_t>(s)];
        k.square_markers = true;
        keys.push_back(k);
    }
    legend(img, f, keys);
    return img;
}

}  // namespace umf::bench::plot
