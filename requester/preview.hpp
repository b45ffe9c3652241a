// The camera preview while grabbing or putting: the frame, a crosshair at
// its centre (the point a grab takes or a put gives to), and whether the
// field is locked, in a way nobody can miss: a red banner while searching, a
// green ring and what is there once locked. Keys: space or Enter grabs (or
// puts), q or Esc quits.
#pragma once

#include <string>

#include <opencv2/core.hpp>

namespace umf::requester {

enum class PreviewState { searching, locked, acting };

enum class PreviewKey { none, act, quit };

struct PreviewStatus {
    PreviewState state = PreviewState::searching;
    std::string target_title;  // what is at the aim, when the provider said
    std::string target_kind;   // "url", "file", "snapshot", "none" or empty
    std::string provider;      // "desk-1", shown in the corner
    bool auto_act = false;     // the hint line says a steady aim grabs (puts)
    std::string verb = "grab";  // "grab" or "put"
    std::string message;        // while acting: what is happening ("waiting for the screen...")
    bool another_screen = false;  // searching: the field in view is another screen's
};

class Preview {
public:
    // `window_name` ("umf-requester grab"): the window's title is it and
    // the screen the status names, and follows a switch to another screen.
    explicit Preview(std::string window_name);
    ~Preview();
    Preview(const Preview&) = delete;
    Preview& operator=(const Preview&) = delete;

    // Draws the frame (8-bit grey, BGR or BGRA) with the overlay and waits
    // up to wait_ms (at least 1) for a key; closing the window counts as quit.
    PreviewKey show(const cv::Mat& frame, const PreviewStatus& status, int wait_ms = 1);

    // The picture show() puts in the window (BGR), without a window.
    static cv::Mat render(const cv::Mat& frame, const PreviewStatus& status);

private:
    std::string title_;     // the window's name, which OpenCV knows it by
    std::string captioned_;  // the screen its title names
    bool shown_ = false;
};

}  // namespace umf::requester
