#include "requester/frame_source.hpp"

#include <cerrno>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <new>
#include <system_error>
#include <utility>

#include <opencv2/core/utils/logger.hpp>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/videoio.hpp>

#include "requester/cli.hpp"

namespace umf::requester {

namespace {

namespace fs = std::filesystem;

// The file's bytes, or why they cannot be had.
std::optional<std::vector<unsigned char>> read_bytes(const std::string& path, std::string& why) {
    std::error_code ec;
    const auto status = fs::status(path, ec);
    if (!fs::exists(status)) {
        why = ec && ec != std::errc::no_such_file_or_directory ? ec.message() : "no such file";
        return std::nullopt;
    }
    if (fs::is_directory(status)) {
        why = "it is a directory";
        return std::nullopt;
    }
    std::ifstream in(path, std::ios::binary);
    if (!in) {
        why = std::strerror(errno);
        return std::nullopt;
    }
    // Read in pieces up to the limit, so that a fifo or a file still growing
    // is handled like a plain file.
    std::vector<unsigned char> bytes;
    char chunk[1 << 16];
    while (in.read(chunk, sizeof chunk) || in.gcount() > 0) {
        bytes.insert(bytes.end(), chunk, chunk + in.gcount());
        if (bytes.size() > kMaxImageFileBytes) {
            why = "the file is larger than the limit of " + std::to_string(kMaxImageFileBytes >> 20) + " MiB";
            return std::nullopt;
        }
    }
    if (in.bad()) {
        why = "read error";
        return std::nullopt;
    }
    return bytes;
}

class ImageFiles : public FrameSource {
public:
    explicit ImageFiles(std::vector<std::string> paths) : paths_(std::move(paths)) {}

    std::optional<Frame> next() override {
        if (next_ >= paths_.size()) return std::nullopt;
        const int index = static_cast<int>(next_);
        return read_image_file(paths_[next_++], index);
    }

private:
    std::vector<std::string> paths_;
    std::size_t next_ = 0;
};

class VideoFile : public FrameSource {
public:
    explicit VideoFile(const std::string& path) : path_(path) {
        // VideoCapture also opens streams ("rtsp://...") and numbered image
        // files ("frame_%03d.png"), which are no files of their own.
        const bool pattern_or_url = path.find('%') != std::string::npos || path.find("://") != std::string::npos;
        std::error_code ec;
        if (!pattern_or_url && !fs::exists(path, ec)) throw InputError("cannot open video " + path + ": no such file");
        if (fs::is_directory(path, ec)) throw InputError("cannot open video " + path + ": it is a directory");
        // Every backend that fails to open the file logs an error of its
        // own; the one message that matters is ours below.
        const auto level = cv::utils::logging::setLogLevel(cv::utils::logging::LOG_LEVEL_SILENT);
        bool opened = false;
        std::string why = "not a video OpenCV can read";
        try {
            opened = capture_.open(path, cv::CAP_ANY);
        } catch (const cv::Exception& e) {
            why = e.err;
        }
        cv::utils::logging::setLogLevel(level);
        if (!opened) throw InputError("cannot open video " + path + ": " + why);
    }

    double fps() const override {
        const double fps = capture_.get(cv::CAP_PROP_FPS);
        return std::isfinite(fps) && fps > 0 && fps < 1000 ? fps : 0;
    }

    std::optional<Frame> next() override {
        if (done_) return std::nullopt;
        Frame f;
        f.index = index_;
        f.name = path_;
        try {
            if (!capture_.read(f.pixels) || f.pixels.empty()) {
                // VideoCapture does not tell a broken frame from the end of
                // the file: both end the video.
                done_ = true;
                return std::nullopt;
            }
        } catch (const cv::Exception& e) {
            done_ = true;
            f.pixels.release();
            f.error = "cannot decode frame " + std::to_string(index_) + " of " + path_ + ": " + e.err;
        }
        ++index_;
        return f;
    }

private:
    std::string path_;
    cv::VideoCapture capture_;
    int index_ = 0;
    bool done_ = false;
};

class Camera : public FrameSource {
public:
    explicit Camera(int index) : name_("camera " + std::to_string(index)) {
        const auto level = cv::utils::logging::setLogLevel(cv::utils::logging::LOG_LEVEL_SILENT);
        bool opened = false;
        std::string why = "no such camera, or it is busy";
        try {
            opened = capture_.open(index, cv::CAP_ANY);
        } catch (const cv::Exception& e) {
            why = e.err;
        }
        cv::utils::logging::setLogLevel(level);
        if (!opened) throw InputError("cannot open " + name_ + ": " + why);
        // Frames queued in the driver are old by the time they are read: a
        // short queue keeps the preview and the aim current.
        capture_.set(cv::CAP_PROP_BUFFERSIZE, 1);
    }

    std::optional<Frame> next() override {
        Frame f;
        f.index = index_++;
        f.name = name_;
        try {
            if (!capture_.read(f.pixels) || f.pixels.empty()) return std::nullopt;  // unplugged
        } catch (const cv::Exception& e) {
            f.pixels.release();
            f.error = "cannot read " + name_ + ": " + e.err;
        }
        return f;
    }
    double fps() const override {
        const double fps = capture_.get(cv::CAP_PROP_FPS);
        return std::isfinite(fps) && fps > 0 && fps < 1000 ? fps : 0;
    }
    bool live() const override { return true; }

private:
    std::string name_;
    cv::VideoCapture capture_;
    int index_ = 0;
};

}  // namespace

std::unique_ptr<FrameSource> camera(int index) { return std::make_unique<Camera>(index); }

Frame read_image_file(const std::string& path, int index) {
    Frame f;
    f.index = index;
    f.name = path;
    std::string why;
    try {
        if (auto bytes = read_bytes(path, why)) {
            if (bytes->empty())
                why = "the file is empty";
            else {
                f.pixels = cv::imdecode(*bytes, cv::IMREAD_COLOR);
                if (f.pixels.empty()) why = "not an image OpenCV can decode";
            }
        }
    } catch (const cv::Exception& e) {
        why = "OpenCV: " + e.err;
    } catch (const std::bad_alloc&) {
        why = "out of memory";
    }
    if (!why.empty()) {
        f.pixels.release();
        f.error = "cannot decode " + path + ": " + why;
    }
    return f;
}

std::unique_ptr<FrameSource> image_files(std::vector<std::string> paths) {
    return std::make_unique<ImageFiles>(std::move(paths));
}

std::unique_ptr<FrameSource> video_file(const std::string& path) { return std::make_unique<VideoFile>(path); }

}  // namespace umf::requester
