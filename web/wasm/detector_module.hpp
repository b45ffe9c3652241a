// The phone client's detector: shared/'s Detector and Tracker behind a small
// C API for WebAssembly (detector_module.cpp, built by web/CMakeLists.txt as
// umf-detector.js + umf-detector.wasm). web/wasm/detector.js wraps it for the
// page's Web Worker.
//
// One handle = one field's Detector and a Tracker over it, plus two buffers
// owned by the module and reused from frame to frame: the frame buffer the
// caller copies pixels into (RGBA8 as VideoFrame.copyTo and getImageData give
// them, or 8-bit grey) and the grey image the detector reads. A frame is
// tracked in three steps:
//   p = umf_frame_buffer(h, w, hgt);   // pointer into wasm memory, w*hgt*4 bytes
//   HEAPU8.set(pixels, p);             // one copy
//   r = umf_track(h, w, hgt, UMF_FORMAT_RGBA, w / 2, hgt / 2);
// and r points to a UmfTrackResult, valid until the next call on the handle.
//
// Nothing here throws into JavaScript: errors are a null handle or result,
// with umf_last_error() saying why.
#pragma once

#include <cstdint>

extern "C" {

enum UmfFormat : std::int32_t {
    UMF_FORMAT_GREY = 0,  // one byte a pixel, width*height bytes
    UMF_FORMAT_RGBA = 1,  // four bytes a pixel, R G B A; grey = BT.601 luma as umf::to_luma
};

enum UmfState : std::int32_t {
    UMF_STATE_SEARCHING = 0,  // TrackState::searching
    UMF_STATE_LOCKED = 1,     // TrackState::locked
    UMF_STATE_LOST = 2,       // TrackState::lost
};

// What one frame gave. Only doubles and 32-bit integers, every field at an
// offset that is a multiple of its size, so JavaScript reads it through
// HEAPF64 / HEAP32 at fixed offsets (detector.js lists them; the static
// asserts in detector_module.cpp keep them fixed).
struct UmfTrackResult {
    double point[2];       //  0: field point (u, v) of the aim, modules; the tracker's smoothed
                           //     aim_field when locked, NaN otherwise
    double confidence;     // 16: as the native requester sends it in `aim`: the detection's
                           //     confidence, 0 when not finite, clamped to [0, 1]; 0 when not found
    double H[9];           // 24: image -> field homography, row-major; identity when not found
    double ms;             // 96: wall time of umf_track (grey conversion included)
    double grey_ms;        // 104: of which the RGBA -> grey conversion
    double detect_ms;      // 112: the detector's own total (Detection::times.total_ms)
    double raw_point[2];   // 120: this frame's unsmoothed aim point (Detection::aim_field)
    std::int32_t state;    // 136: UmfState
    std::int32_t found;    // 140: this frame verified a place (Detection::found)
    std::int32_t windows;  // 144: windows that agreed on the place
    std::int32_t used_prior;         // 148: the lock came from the prediction
    std::int32_t frames_since_lock;  // 152
    std::int32_t edges_fitted;       // 156
    std::int32_t another_field;      // 160: not found, for another screen's field is under the aim
                                     //      (Detection::another_field)
    std::int32_t demodulated;        // 164: the place is the pulse search's, found over the frames
                                     //      kept or carried from it (PulseTrackResult::demodulated)
};

// The pulse a provider announces (its welcome's overlay waveform).
enum UmfPulse : std::int32_t {
    UMF_PULSE_NONE = 0,  // no pulse search: each frame tracked on its own
    UMF_PULSE_SINE = 1,
    UMF_PULSE_TRIANGLE = 2,
};

// A tracker for the field in `field_json` (a umf-field/1 object, the
// `field.definition` of the provider's welcome; UTF-8, `length` bytes, no
// terminator needed). Null when the text is not a valid field or the field
// cannot be detected (umf_last_error() says why).
void* umf_create(const char* field_json, int length);
void umf_destroy(void* handle);

// The buffer to copy a frame into: at least width*height*4 bytes, so it takes
// RGBA; grey frames use the first width*height. Grows (and moves) only when a
// larger frame comes; null for sizes the detector does not take.
std::uint8_t* umf_frame_buffer(void* handle, int width, int height);

// Runs Tracker::update (PulseTracker::update once a pulse is set) on the
// frame in the frame buffer, aiming at image point (aim_x, aim_y) in pixels
// (continuous coordinates: the image centre is (width / 2, height / 2), what
// the native requester aims at). `time_ms`: when the frame was taken, in
// milliseconds on any clock that runs forward (VideoFrame.timestamp / 1000),
// or NaN: the pulse is then fitted at the frame rate set. Null on bad
// arguments (umf_last_error()).
const UmfTrackResult* umf_track(void* handle, int width, int height, int format, double aim_x, double aim_y,
                                double time_ms);

// Forgets the lock: the next frame is searched from scratch.
void umf_reset(void* handle);

// The camera's frame rate (frames a second), for a tracker that keeps up
// with it: each frame without a lock then runs the first scan and the
// search's next steps, held to kSpreadFrameShare of the time between two
// frames on this device (TrackerOptions::spread_search, frame_ms). 0: every search on
// every frame without a lock (the default; what a photo wants). Forgets the
// lock. Returns 0, or -1 for a rate that is
// negative or not finite (umf_last_error()).
int umf_set_frame_rate(void* handle, double frames_per_second);

// The screen's field pulses (`pulse`, every `period_s` seconds: the welcome's
// overlay): frames where the tracker holds no lock are also registered onto
// each other and searched together for a field too faint for any one of
// them (shared/detect/pulse_tracker.hpp). `opacity_min` and `opacity_max`:
// the overlay's range, with which the content is taken out of the frames
// searched together (PulseShape; both 0: not known). UMF_PULSE_NONE turns
// that off. Forgets the lock. Returns 0, or -1 for an unknown pulse, a
// period outside 0.5..60 s or a range outside 0..1 (umf_last_error()).
int umf_set_pulse(void* handle, int pulse, double period_s, double opacity_min, double opacity_max);

// The grey image of the last frame (width*height bytes), for tests and debugging.
const std::uint8_t* umf_grey_buffer(void* handle);
// The stage that ended the last frame's search ("" when found), NUL-terminated.
const char* umf_failure(void* handle);
// Why the last call failed, NUL-terminated; "" after a success.
const char* umf_last_error();
// sizeof(UmfTrackResult), so the JavaScript side can check its offsets.
int umf_result_size();
}
