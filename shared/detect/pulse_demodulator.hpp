// The field out of a pulsing screen, over frames. The provider mixes the
// field at an opacity that follows its preset's pulse while the content
// under it stays; each pixel a camera sees is then
//     I = (1 - a) C + a F = C + a (F - C)
// (C the content, F the field's module colour, a the opacity). Over frames
// of the same view at different opacities, each pixel's grey level is a
// straight line in a, its slope F - C: the field at full contrast beside
// the content, where a single frame holds the content at 1 - a and the
// field at a. At a pulse of a few percent the field is lost in one frame's
// content (at 0.04 the content is 24 times as strong) and plain in the
// slope (equal to it). The slope's noise is the frames' noise over the
// spread of the opacities (their standard deviation) and the square root of
// the frames: a sine pulse between 0.01 and 0.04 (spread 0.0106) over the
// 19 frames of its rise, with a camera noise of 2 grey levels, leaves about
// 22 levels of noise in the demodulated image, whose field modules are 127
// levels from its middle grey.
//
// The frames must show the screen in the same place (a camera at rest, or
// frames resampled onto the first; the caller registers them); the
// detector reads the demodulated image as it reads a frame.
#pragma once

#include <cstdint>
#include <optional>
#include <utility>
#include <vector>

#include "shared/detect/image.hpp"

namespace umf {

class PulseDemodulator {
public:
    // `forget`: each frame added multiplies the weight of those before it
    // by 1 - forget (0 keeps every frame alike; 0.1 remembers about the
    // last ten), so that a view that drifts leaves the old frames behind.
    explicit PulseDemodulator(double forget = 0);

    // A frame and the field's opacity when it was taken. A frame of another
    // size than the first starts over from it. Throws
    // std::invalid_argument for a view describe_invalid rejects or an
    // opacity outside [0, 1].
    void add(const GreyView& frame, double opacity);
    void reset();

    // The frames' weight (their count, less what was forgotten) and the
    // spread of their opacities (standard deviation, weighted): a slope is
    // only as good as the opacities it spans.
    double weight() const { return weight_; }
    int width() const { return width_; }
    double opacity_spread() const;

    // The slope F - C of every pixel (-255..255) as a grey image, 127.5 +
    // slope / 2 rounded and clamped; a view of a buffer of its own, valid
    // until the next call. An empty view before two frames at different
    // opacities. With opacities known only up to a factor (a course found
    // from the frames, pulse_course.hpp), `SlopeScale::spread` scales the
    // slope so that its mean magnitude is kSpreadLevels grey levels.
    enum class SlopeScale { opacity, spread };
    static constexpr double kSpreadLevels = 48;
    GreyView field_image(SlopeScale scale = SlopeScale::opacity);

    // The slope as field_image gives it at SlopeScale::spread, with what
    // the content leaks into it over a moving view taken out
    // (content_leakage.hpp, tiles `tile` pixels a side). A view of the same
    // buffer as field_image's.
    GreyView content_free_field_image(int tile);

    // What each pixel would be at opacity 1, the field alone: each frame's
    // line I = C + a (F - C) followed out to a = 1, where the content C is
    // gone. The values given to add are taken for opacities scaled linearly
    // from `opacity_at_zero` (given 0) to `opacity_at_one` (given 1): a
    // course found from the frames is the pulse only up to its range, which
    // the provider announces. A view of the same buffer as field_image's.
    GreyView full_opacity_image(double opacity_at_zero, double opacity_at_one);

private:
    std::optional<std::pair<double, double>> slope_terms() const;

    double forget_;
    int width_ = 0, height_ = 0;
    // Weighted sums over the frames: of 1, a, a^2 (scalars), of I and a I
    // (per pixel).
    int frames_ = 0;
    double weight_ = 0, sum_a_ = 0, sum_aa_ = 0;
    std::vector<float> sum_i_, sum_ai_;
    std::vector<std::uint8_t> image_;
};

}  // namespace umf
