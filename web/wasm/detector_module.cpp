// The C API of detector_module.hpp over shared/'s Detector and Tracker.
#include "web/wasm/detector_module.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstddef>
#include <exception>
#include <limits>
#include <memory>
#include <new>
#include <optional>
#include <string>
#include <vector>

#ifdef __EMSCRIPTEN__
#include <emscripten/emscripten.h>
#else
#define EMSCRIPTEN_KEEPALIVE
#endif
#ifdef __wasm_simd128__
#include <wasm_simd128.h>
#endif

#include "shared/aiming/aim.hpp"
#include "shared/detect/detector.hpp"
#include "shared/detect/image.hpp"
#include "shared/detect/pulse_tracker.hpp"
#include "shared/detect/tracker.hpp"
#include "shared/field/field_io.hpp"
#include "shared/overlay/preset.hpp"
#include "shared/overlay/pulse_shape.hpp"

static_assert(offsetof(UmfTrackResult, confidence) == 16);
static_assert(offsetof(UmfTrackResult, H) == 24);
static_assert(offsetof(UmfTrackResult, ms) == 96);
static_assert(offsetof(UmfTrackResult, raw_point) == 120);
static_assert(offsetof(UmfTrackResult, state) == 136);
static_assert(offsetof(UmfTrackResult, edges_fitted) == 156);
static_assert(offsetof(UmfTrackResult, another_field) == 160);
static_assert(offsetof(UmfTrackResult, demodulated) == 164);
static_assert(sizeof(UmfTrackResult) == 168);

namespace {

using Clock = std::chrono::steady_clock;

std::string g_last_error;

struct Instance {
    explicit Instance(umf::Field f) : field(std::move(f)), detector(field), tracker(detector) {}
    umf::Field field;
    umf::Detector detector;
    umf::TrackerOptions tracking;
    umf::Tracker tracker;
    // Set with a pulse (umf_set_pulse): tracks in the tracker's place.
    std::optional<umf::PulseShape> pulse;
    std::unique_ptr<umf::PulseTracker> pulse_tracker;
    // Made anew for new tracking options or a new pulse.
    void restart() {
        tracker = umf::Tracker(detector, tracking);
        pulse_tracker.reset();
        if (!pulse) return;
        umf::PulseSearchOptions options;
        options.shape = pulse;
        pulse_tracker = std::make_unique<umf::PulseTracker>(detector, tracking, options);
    }
    std::vector<std::uint8_t> frame;  // what the caller copies into (RGBA or grey)
    std::vector<std::uint8_t> grey;   // what the detector reads
    const std::uint8_t* last_grey = nullptr;  // the last frame's grey (grey buffer or frame buffer)
    UmfTrackResult result{};
    std::string failure;
};

Instance* instance(void* handle) { return static_cast<Instance*>(handle); }

bool frame_size_ok(int width, int height) {
    return width > 0 && height > 0 && width <= umf::kMaxImageSideForDetection &&
           height <= umf::kMaxImageSideForDetection;
}

double ms_since(Clock::time_point t0) {
    return std::chrono::duration<double, std::milli>(Clock::now() - t0).count();
}

// BT.601 luma of RGBA pixels, bit for bit what umf::to_luma computes
// ((77 r + 150 g + 29 b + 128) >> 8; the largest sum, 65408, fits 16 bits),
// sixteen pixels per step with WebAssembly SIMD.
void rgba_to_grey(const std::uint8_t* rgba, std::uint8_t* grey, std::size_t n) {
    std::size_t i = 0;
#ifdef __wasm_simd128__
    const v128_t wr = wasm_i16x8_splat(77), wg = wasm_i16x8_splat(150), wb = wasm_i16x8_splat(29),
                 round = wasm_i16x8_splat(128);
    for (; i + 16 <= n; i += 16) {
        const std::uint8_t* p = rgba + 4 * i;
        const v128_t a = wasm_v128_load(p), b = wasm_v128_load(p + 16), c = wasm_v128_load(p + 32),
                     d = wasm_v128_load(p + 48);
        // Channel c of the sixteen pixels: bytes c, c+4, ... of a and b, then of c and d.
        const v128_t rab = wasm_i8x16_shuffle(a, b, 0, 4, 8, 12, 16, 20, 24, 28, 0, 0, 0, 0, 0, 0, 0, 0);
        const v128_t rcd = wasm_i8x16_shuffle(c, d, 0, 4, 8, 12, 16, 20, 24, 28, 0, 0, 0, 0, 0, 0, 0, 0);
        const v128_t gab = wasm_i8x16_shuffle(a, b, 1, 5, 9, 13, 17, 21, 25, 29, 0, 0, 0, 0, 0, 0, 0, 0);
        const v128_t gcd = wasm_i8x16_shuffle(c, d, 1, 5, 9, 13, 17, 21, 25, 29, 0, 0, 0, 0, 0, 0, 0, 0);
        const v128_t bab = wasm_i8x16_shuffle(a, b, 2, 6, 10, 14, 18, 22, 26, 30, 0, 0, 0, 0, 0, 0, 0, 0);
        const v128_t bcd = wasm_i8x16_shuffle(c, d, 2, 6, 10, 14, 18, 22, 26, 30, 0, 0, 0, 0, 0, 0, 0, 0);
        auto luma8 = [&](v128_t r, v128_t g, v128_t bl) {  // eight pixels, 16-bit lanes
            v128_t s = wasm_i16x8_add(wasm_i16x8_mul(wasm_u16x8_extend_low_u8x16(r), wr), round);
            s = wasm_i16x8_add(s, wasm_i16x8_mul(wasm_u16x8_extend_low_u8x16(g), wg));
            s = wasm_i16x8_add(s, wasm_i16x8_mul(wasm_u16x8_extend_low_u8x16(bl), wb));
            return wasm_u16x8_shr(s, 8);
        };
        wasm_v128_store(grey + i, wasm_u8x16_narrow_i16x8(luma8(rab, gab, bab), luma8(rcd, gcd, bcd)));
    }
#endif
    for (; i < n; ++i) {
        const std::uint8_t* p = rgba + 4 * i;
        grey[i] = static_cast<std::uint8_t>((77 * p[0] + 150 * p[1] + 29 * p[2] + 128) >> 8);
    }
}

void fill(UmfTrackResult& out, const umf::TrackResult& r) {
    const double nan = std::numeric_limits<double>::quiet_NaN();
    const umf::Detection& d = r.detection;
    out.state = r.state == umf::TrackState::locked ? UMF_STATE_LOCKED
                : r.state == umf::TrackState::lost ? UMF_STATE_LOST
                                                   : UMF_STATE_SEARCHING;
    out.found = d.found ? 1 : 0;
    const bool locked = r.state == umf::TrackState::locked;
    out.point[0] = locked ? r.aim_field.x() : nan;
    out.point[1] = locked ? r.aim_field.y() : nan;
    out.raw_point[0] = d.found ? d.aim_field.x() : nan;
    out.raw_point[1] = d.found ? d.aim_field.y() : nan;
    // What the native requester sends as the aim's confidence.
    out.confidence = d.found ? umf::aiming::aim_confidence(d) : 0.0;
    const Eigen::Matrix3d H = d.found ? d.image_to_field : Eigen::Matrix3d::Identity();
    for (int i = 0; i < 9; ++i) out.H[i] = H(i / 3, i % 3);
    out.windows = d.windows;
    out.used_prior = r.used_prior ? 1 : 0;
    out.frames_since_lock = r.frames_since_lock;
    out.edges_fitted = d.edges_fitted;
    out.another_field = !d.found && d.another_field ? 1 : 0;
    out.detect_ms = d.times.total_ms;
}

}  // namespace

extern "C" {

EMSCRIPTEN_KEEPALIVE void* umf_create(const char* field_json, int length) {
    g_last_error.clear();
    if (!field_json || length < 0 || static_cast<std::size_t>(length) > umf::kMaxFieldFileBytes) {
        g_last_error = "umf_create: no field text, or longer than a field file may be";
        return nullptr;
    }
    // parse_field and the detector's window index throw for a bad field
    // (std::invalid_argument, umf::FieldFileError); nothing else should.
    try {
        umf::Field field = umf::parse_field(std::string(field_json, static_cast<std::size_t>(length)), "welcome field");
        return new Instance(std::move(field));
    } catch (const std::bad_alloc&) {
        g_last_error = "umf_create: out of memory";
    } catch (const std::exception& e) {
        g_last_error = e.what();
    }
    return nullptr;
}

EMSCRIPTEN_KEEPALIVE void umf_destroy(void* handle) { delete instance(handle); }

EMSCRIPTEN_KEEPALIVE std::uint8_t* umf_frame_buffer(void* handle, int width, int height) {
    g_last_error.clear();
    Instance* in = instance(handle);
    if (!in || !frame_size_ok(width, height)) {
        g_last_error = "umf_frame_buffer: no handle, or a frame size the detector does not take";
        return nullptr;
    }
    const std::size_t bytes = static_cast<std::size_t>(width) * static_cast<std::size_t>(height) * 4;
    try {
        // Grows only: a vector never gives its capacity back on resize.
        if (in->frame.size() < bytes) {
            in->frame.resize(bytes);
            in->last_grey = nullptr;  // it may have pointed into the old frame buffer
        }
    } catch (const std::bad_alloc&) {
        g_last_error = "umf_frame_buffer: out of memory";
        return nullptr;
    }
    return in->frame.data();
}

EMSCRIPTEN_KEEPALIVE const UmfTrackResult* umf_track(void* handle, int width, int height, int format, double aim_x,
                                                     double aim_y, double time_ms) {
    const auto t0 = Clock::now();
    g_last_error.clear();
    Instance* in = instance(handle);
    if (!in || !frame_size_ok(width, height) || (format != UMF_FORMAT_GREY && format != UMF_FORMAT_RGBA) ||
        !std::isfinite(aim_x) || !std::isfinite(aim_y)) {
        g_last_error = "umf_track: no handle, a bad frame size or format, or an aim point that is not finite";
        return nullptr;
    }
    const std::size_t n = static_cast<std::size_t>(width) * static_cast<std::size_t>(height);
    if (in->frame.size() < (format == UMF_FORMAT_RGBA ? 4 * n : n)) {
        g_last_error = "umf_track: the frame buffer is smaller than the frame; call umf_frame_buffer first";
        return nullptr;
    }
    UmfTrackResult& out = in->result;
    out = UmfTrackResult{};
    umf::GreyView view;
    if (format == UMF_FORMAT_RGBA) {
        try {
            if (in->grey.size() < n) in->grey.resize(n);
        } catch (const std::bad_alloc&) {
            g_last_error = "umf_track: out of memory";
            return nullptr;
        }
        rgba_to_grey(in->frame.data(), in->grey.data(), n);
        view = {in->grey.data(), width, height, width};
    } else {
        view = {in->frame.data(), width, height, width};
    }
    in->last_grey = view.data;
    out.grey_ms = ms_since(t0);
    try {
        const Eigen::Vector2d aim(aim_x, aim_y);
        if (in->pulse_tracker) {
            std::optional<double> time_s;
            if (std::isfinite(time_ms)) time_s = time_ms / 1000;
            const umf::PulseTrackResult r = in->pulse_tracker->update(view, aim, time_s);
            fill(out, r.track);
            out.demodulated = r.demodulated ? 1 : 0;
            in->failure = r.track.detection.failure;
        } else {
            const umf::TrackResult r = in->tracker.update(view, aim);
            fill(out, r);
            in->failure = r.detection.failure;
        }
    } catch (const std::exception& e) {
        g_last_error = std::string("umf_track: ") + e.what();
        return nullptr;
    }
    out.ms = ms_since(t0);
    return &out;
}

EMSCRIPTEN_KEEPALIVE void umf_reset(void* handle) {
    Instance* in = instance(handle);
    if (!in) return;
    in->tracker.reset();
    if (in->pulse_tracker) in->pulse_tracker->reset();
}

EMSCRIPTEN_KEEPALIVE int umf_set_frame_rate(void* handle, double frames_per_second) {
    g_last_error.clear();
    Instance* in = instance(handle);
    if (!in || !std::isfinite(frames_per_second) || frames_per_second < 0) {
        g_last_error = "umf_set_frame_rate: no handle, or a rate that is negative or not finite";
        return -1;
    }
    umf::TrackerOptions options;
    if (frames_per_second > 0) {
        options.spread_search = true;
        options.frame_ms = umf::kSpreadFrameShare * 1000 / frames_per_second;
    }
    in->tracking = options;
    in->restart();
    return 0;
}

EMSCRIPTEN_KEEPALIVE int umf_set_pulse(void* handle, int pulse, double period_s, double opacity_min,
                                       double opacity_max) {
    g_last_error.clear();
    Instance* in = instance(handle);
    if (!in) {
        g_last_error = "umf_set_pulse: no handle";
        return -1;
    }
    if (!(opacity_min >= 0 && opacity_min <= opacity_max && opacity_max <= 1)) {
        g_last_error = "umf_set_pulse: an opacity range outside 0..1";
        return -1;
    }
    if (pulse == UMF_PULSE_NONE) {
        in->pulse.reset();
    } else if ((pulse == UMF_PULSE_SINE || pulse == UMF_PULSE_TRIANGLE) && period_s >= umf::overlay::kMinPeriodS &&
               period_s <= umf::overlay::kMaxPeriodS) {
        in->pulse = umf::overlay::announced_pulse_shape(
            pulse == UMF_PULSE_SINE ? umf::overlay::Waveform::sine : umf::overlay::Waveform::triangle, period_s,
            opacity_min, opacity_max);
    } else {
        g_last_error = "umf_set_pulse: an unknown pulse, or a period outside 0.5..60 s";
        return -1;
    }
    try {
        in->restart();
    } catch (const std::bad_alloc&) {
        g_last_error = "umf_set_pulse: out of memory";
        return -1;
    }
    return 0;
}

EMSCRIPTEN_KEEPALIVE const std::uint8_t* umf_grey_buffer(void* handle) {
    Instance* in = instance(handle);
    return in ? in->last_grey : nullptr;
}

EMSCRIPTEN_KEEPALIVE const char* umf_failure(void* handle) {
    Instance* in = instance(handle);
    return in ? in->failure.c_str() : "";
}

EMSCRIPTEN_KEEPALIVE const char* umf_last_error() { return g_last_error.c_str(); }

EMSCRIPTEN_KEEPALIVE int umf_result_size() { return static_cast<int>(sizeof(UmfTrackResult)); }

}  // extern "C"
