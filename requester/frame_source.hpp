// Where frames come from: a list of image files or a video, one frame at a
// time, so a long video never has to fit in memory. A frame that cannot be
// read is a value with the reason, not an exception: one bad file in a list
// must not stop the others.
#pragma once

#include <cstddef>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include <opencv2/core.hpp>

namespace umf::requester {

struct Frame {
    int index = 0;      // 0-based over all frames the source has given
    std::string name;   // the image file, or the video file
    cv::Mat pixels;     // CV_8UC3 (BGR) from files; a video backend may also give CV_8UC1 or CV_8UC4
    std::string error;  // set (and pixels empty) when the frame could not be read
};

class FrameSource {
public:
    virtual ~FrameSource() = default;
    // The next frame, or nothing once the source is exhausted.
    virtual std::optional<Frame> next() = 0;
    // Frames per second of a recording, 0 when unknown (image files).
    virtual double fps() const { return 0; }
    // Frames arrive in real time (a camera): time is the wall clock's, not
    // the frame count's.
    virtual bool live() const { return false; }
};

// Image files larger than this are not images from a camera.
inline constexpr std::size_t kMaxImageFileBytes = std::size_t{256} << 20;

// Each path in turn, decoded by OpenCV. A file that is missing, unreadable,
// too large or not an image gives a frame with
// error = "cannot decode PATH: why".
std::unique_ptr<FrameSource> image_files(std::vector<std::string> paths);

// The frames of a video file (or whatever else cv::VideoCapture opens: a
// stream URL, numbered images "frame_%03d.png"). Throws InputError (cli.hpp)
// when it cannot be opened.
std::unique_ptr<FrameSource> video_file(const std::string& path);

// Camera `index` (/dev/videoINDEX on Linux), live. Throws InputError when it
// cannot be opened.
std::unique_ptr<FrameSource> camera(int index);

// One image file as a frame (what image_files gives for each path).
Frame read_image_file(const std::string& path, int index);

}  // namespace umf::requester
