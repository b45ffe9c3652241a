// The course of a field's pulse over frames of a view at rest, from the
// frames alone: the page and `locate --sequence` know the preset's period
// and waveform but not the provider's clock, and a pulse may be any shape.
// Each pixel varies over time as a(t) (F - C) plus noise (pulse_demodulator.hpp),
// so the frames less their mean are one course a(t) times one image, and
// that course is the leading eigenvector of the frames' covariance over
// time (an N x N matrix for N frames, read on a sample of the pixels).
// Its sign is not known: the caller reads the demodulated image and its
// inverse (what the other sign gives) and keeps the
// one the detector finds the field in (a field seen inverted matches none
// of its own windows).
#pragma once

#include <Eigen/Core>
#include <span>
#include <vector>

#include "shared/detect/image.hpp"

namespace umf {

struct PulseCourse {
    // Per frame, with mean 0 and the largest magnitude 1; empty for fewer
    // than three frames or frames of different sizes.
    std::vector<double> level;
    // The share of the frames' variation over time that the course
    // explains, 0..1: near 1 for a pulse well above the noise, near 1 / N
    // (N frames) for noise alone.
    double share = 0;
    // The frames' covariance over time (N x N, on the pixels read): how
    // much of their variation any other course would explain.
    Eigen::MatrixXd covariance;
};

// `sample_step`: every this many pixels along rows and columns are read.
PulseCourse find_pulse_course(std::span<const GreyView> frames, int sample_step = 4);

}  // namespace umf
