#include "requester/preview.hpp"

#include <algorithm>
#include <cmath>

#include <opencv2/highgui.hpp>
#include <opencv2/imgproc.hpp>

namespace umf::requester {

namespace {

const cv::Scalar kRed(40, 40, 220), kGreen(60, 200, 60), kAmber(0, 170, 255), kWhite(255, 255, 255),
    kBlack(0, 0, 0);

// OpenCV's Hershey fonts are ASCII only: dashes and accented Latin letters
// are drawn as their nearest ASCII, anything else as '?', rather than the
// garbage the font would make of UTF-8.
std::string ascii(const std::string& s, std::size_t max_chars) {
    static const char* const kLatin1 = "AAAAAAACEEEEIIIIDNOOOOOxOUUUUYTsaaaaaaaceeeeiiiidnooooo/ouuuuyty";
    std::string out;
    for (std::size_t i = 0; i < s.size() && out.size() < max_chars;) {
        const auto c = static_cast<unsigned char>(s[i]);
        if (c < 0x80) {
            out += c >= 0x20 && c != 0x7f ? static_cast<char>(c) : ' ';
            ++i;
            continue;
        }
        const int len = c >= 0xF0 ? 4 : c >= 0xE0 ? 3 : c >= 0xC0 ? 2 : 1;
        unsigned cp = len == 1 ? 0xFFFD : c & (0x7F >> len);
        for (int k = 1; k < len; ++k)
            cp = i + k < s.size() ? (cp << 6) | (static_cast<unsigned char>(s[i + k]) & 0x3F) : 0xFFFD;
        i += static_cast<std::size_t>(len);
        if (cp >= 0xC0 && cp <= 0xFF)
            out += kLatin1[cp - 0xC0];
        else if (cp == 0x2013 || cp == 0x2014 || cp == 0x2212)
            out += '-';
        else if (cp == 0x2018 || cp == 0x2019)
            out += '\'';
        else if (cp == 0x201C || cp == 0x201D)
            out += '"';
        else if (cp == 0x2026)
            out += "...";
        else if (cp == 0xA0)
            out += ' ';
        else
            out += '?';
    }
    return out;
}

void banner(cv::Mat& img, const std::string& text, const cv::Scalar& colour, bool top) {
    const double scale = std::max(0.5, img.cols / 1100.0);
    const int thickness = std::max(1, static_cast<int>(std::lround(scale * 2)));
    int base = 0;
    const cv::Size size = cv::getTextSize(text, cv::FONT_HERSHEY_SIMPLEX, scale, thickness, &base);
    const int h = size.height + base + 16;
    const cv::Rect band(0, top ? 0 : img.rows - h, img.cols, h);
    img(band).setTo(colour);
    cv::putText(img, text, {std::max(8, (img.cols - size.width) / 2), band.y + 8 + size.height},
                cv::FONT_HERSHEY_SIMPLEX, scale, kWhite, thickness, cv::LINE_AA);
}

void crosshair(cv::Mat& img, const cv::Scalar& colour) {
    const cv::Point c(img.cols / 2, img.rows / 2);
    const int r = std::max(12, std::min(img.cols, img.rows) / 24);
    for (const auto& [col, w] : {std::pair{kBlack, 4}, std::pair{colour, 2}}) {
        cv::line(img, {c.x - 2 * r, c.y}, {c.x - r / 3, c.y}, col, w, cv::LINE_AA);
        cv::line(img, {c.x + r / 3, c.y}, {c.x + 2 * r, c.y}, col, w, cv::LINE_AA);
        cv::line(img, {c.x, c.y - 2 * r}, {c.x, c.y - r / 3}, col, w, cv::LINE_AA);
        cv::line(img, {c.x, c.y + r / 3}, {c.x, c.y + 2 * r}, col, w, cv::LINE_AA);
    }
}

}  // namespace

Preview::Preview(std::string window_title) : title_(std::move(window_title)) {}

Preview::~Preview() {
    if (!shown_) return;
    try {
        cv::destroyWindow(title_);
        cv::waitKey(1);
    } catch (const cv::Exception&) {
        // The window may already be gone with its display.
    }
}

cv::Mat Preview::render(const cv::Mat& frame, const PreviewStatus& status) {
    cv::Mat img;
    if (frame.channels() == 1)
        cv::cvtColor(frame, img, cv::COLOR_GRAY2BGR);
    else if (frame.channels() == 4)
        cv::cvtColor(frame, img, cv::COLOR_BGRA2BGR);
    else
        img = frame.clone();

    const cv::Point centre(img.cols / 2, img.rows / 2);
    const int ring = std::max(16, std::min(img.cols, img.rows) / 10);
    switch (status.state) {
        case PreviewState::searching:
            // A frame all round as well: the banner alone is easy to miss
            // while looking at the crosshair.
            cv::rectangle(img, {0, 0, img.cols, img.rows}, kRed, std::max(4, img.cols / 80));
            crosshair(img, kRed);
            banner(img, status.another_screen ? "another screen - scan its QR code" : "searching - point at the screen",
                   kRed, true);
            break;
        case PreviewState::locked: {
            crosshair(img, kGreen);
            cv::circle(img, centre, ring, kBlack, 6, cv::LINE_AA);
            cv::circle(img, centre, ring, kGreen, 3, cv::LINE_AA);
            std::string what = status.target_kind.empty() ? "locked" : status.target_kind;
            if (!status.target_title.empty()) what += ": " + status.target_title;
            if (status.target_kind == "none")
                what = status.verb == "put" ? "locked - puts go here" : "locked - nothing to take here";
            banner(img, ascii(what, 80), kGreen, true);
            break;
        }
        case PreviewState::acting:
            crosshair(img, kAmber);
            cv::circle(img, centre, ring, kAmber, 3, cv::LINE_AA);
            banner(img,
                   !status.message.empty() ? ascii(status.message, 80)
                   : status.verb == "put"  ? "putting..."
                                           : "grabbing...",
                   kAmber, true);
            break;
    }
    const std::string hint = status.state == PreviewState::acting ? std::string("q / Esc cancels")
                             : status.auto_act ? "hold steady to " + status.verb + " - q / Esc quits"
                                               : "space / Enter " + status.verb + "s - q / Esc quits";
    banner(img, ascii((status.provider.empty() ? "" : status.provider + " - ") + hint, 100), cv::Scalar(60, 60, 60),
           false);
    return img;
}

PreviewKey Preview::show(const cv::Mat& frame, const PreviewStatus& status, int wait_ms) {
    cv::imshow(title_, render(frame, status));
    shown_ = true;
    if (status.provider != captioned_) {
        captioned_ = status.provider;
        try {
            cv::setWindowTitle(title_, captioned_.empty() ? title_ : title_ + " - " + captioned_);
        } catch (const cv::Exception&) {
            // A highgui backend without titles: the banner names the screen all the same.
        }
    }
    const int key = cv::waitKey(std::max(1, wait_ms));
    // The window's close button: the window is gone, so is the user.
    if (cv::getWindowProperty(title_, cv::WND_PROP_VISIBLE) < 1) return PreviewKey::quit;
    if (key < 0) return PreviewKey::none;
    switch (key & 0xff) {
        case ' ':
        case '\r':
        case '\n':
            return PreviewKey::act;
        case 'q':
        case 'Q':
        case 27:
            return PreviewKey::quit;
        default:
            return PreviewKey::none;
    }
}

}  // namespace umf::requester
