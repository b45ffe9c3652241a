// The phone client's detector for its Web Worker: shared/'s Detector and
// Tracker compiled to WebAssembly (umf-detector.js + .wasm, next to this file
// in web/site/), behind a small object.
//
//   import { createDetector } from './detector.js';
//   const detector = await createDetector(welcome.field.definition);
//   const r = detector.track(rgba, width, height);   // aims at the image centre
//   if (r.state === 'locked') send({ type: 'aim', point: r.point, confidence: r.confidence, ... });
//   detector.reset(); detector.destroy();
//
// Frames are RGBA8 (VideoFrame.copyTo with format RGBA, ImageData.data) or
// 8-bit grey; each is copied once into the module's own buffer.
import { cString, loadModule, withText } from './umf_module.js';

const STATES = ['searching', 'locked', 'lost'];
const FORMATS = { grey: 0, rgba: 1 };
// UmfTrackResult (detector_module.hpp): byte offsets.
const RESULT_SIZE = 168;
const OFF = {
  point: 0, confidence: 16, H: 24, ms: 96, greyMs: 104, detectMs: 112, rawPoint: 120,
  state: 136, found: 140, windows: 144, usedPrior: 148, framesSinceLock: 152, edgesFitted: 156,
  anotherField: 160, demodulated: 164,
};
// UmfPulse (detector_module.hpp): the welcome's overlay waveform.
const PULSES = { none: 0, sine: 1, triangle: 2 };

// fieldJson: the welcome's field definition, as an object or as JSON text.
export async function createDetector(fieldJson, { moduleOptions } = {}) {
  const M = await loadModule(moduleOptions);
  if (M._umf_result_size() !== RESULT_SIZE) throw new Error('umf-detector.wasm does not match detector.js');
  const text = typeof fieldJson === 'string' ? fieldJson : JSON.stringify(fieldJson);
  let handle = withText(M, text, (ptr, n) => M._umf_create(ptr, n));
  if (!handle) throw new Error(cString(M, M._umf_last_error()) || 'umf detector: cannot use the field');

  const alive = () => {
    if (!handle) throw new Error('umf detector: used after destroy()');
  };

  return {
    // pixels: Uint8Array or Uint8ClampedArray (or an ArrayBuffer) of
    // width*height*4 (RGBA) or width*height (grey) bytes. options.format
    // 'rgba' | 'grey' (by default from the length); options.aim [x, y] in
    // image pixels (default the image centre, as the native requester);
    // options.timeMs: when the frame was taken, ms on a clock that runs
    // forward (VideoFrame.timestamp / 1000), for the pulse search's fit.
    track(pixels, width, height, { format, aim, timeMs } = {}) {
      alive();
      const data = pixels instanceof ArrayBuffer ? new Uint8Array(pixels) : pixels;
      const n = width * height;
      const f = format ?? (data.length === 4 * n ? 'rgba' : data.length === n ? 'grey' : null);
      if (!(f in FORMATS)) throw new Error(`umf detector: ${data.length} bytes are neither RGBA nor grey ${width}x${height}`);
      const bytes = f === 'rgba' ? 4 * n : n;
      if (data.length < bytes) throw new Error('umf detector: fewer bytes than the frame needs');
      const buffer = M._umf_frame_buffer(handle, width, height);
      if (!buffer) throw new Error(cString(M, M._umf_last_error()));
      // After _umf_frame_buffer: the memory may have grown, M.HEAPU8 is the current view.
      M.HEAPU8.set(data.length === bytes ? data : data.subarray(0, bytes), buffer);
      const [ax, ay] = aim ?? [width / 2, height / 2];
      const r = M._umf_track(handle, width, height, FORMATS[f], ax, ay, Number.isFinite(timeMs) ? timeMs : NaN);
      if (!r) throw new Error(cString(M, M._umf_last_error()));
      return readResult(M, r, handle);
    },
    // The grey image the last frame was read as (a copy), for tests and debugging.
    grey(width, height) {
      alive();
      const p = M._umf_grey_buffer(handle);
      return p ? M.HEAPU8.slice(p, p + width * height) : null;
    },
    reset() {
      alive();
      M._umf_reset(handle);
    },
    // The camera's frames a second: each frame without a lock then searches
    // what fits in part of the time between two frames on this device (0:
    // every search on every frame, the default). Forgets the lock.
    setFrameRate(framesPerSecond) {
      alive();
      if (M._umf_set_frame_rate(handle, framesPerSecond) !== 0) throw new Error(cString(M, M._umf_last_error()));
    },
    // The screen's pulse as its welcome announces it (overlay.waveform
    // 'sine' | 'triangle', overlay.period_s): frames without a lock are then
    // also searched together for a field too faint for any one of them.
    // 'none' (or a period of 0, a static field) turns that off. `range`:
    // {min, max}, the welcome's overlay.opacity_min and opacity_max, with
    // which the content is taken out of those frames. Forgets the lock.
    setPulse(waveform, periodS, range = { min: 0, max: 0 }) {
      alive();
      const pulse = periodS > 0 ? PULSES[waveform] : PULSES.none;
      if (pulse === undefined) throw new Error(`umf detector: no pulse "${waveform}"`);
      if (M._umf_set_pulse(handle, pulse, periodS > 0 ? periodS : 0, range.min ?? 0, range.max ?? 0) !== 0) throw new Error(cString(M, M._umf_last_error()));
    },
    destroy() {
      if (handle) M._umf_destroy(handle);
      handle = 0;
    },
  };
}

function readResult(M, r, handle) {
  const f64 = M.HEAPF64, i32 = M.HEAP32;
  const d = (off) => f64[(r + off) >> 3];
  const i = (off) => i32[(r + off) >> 2];
  const state = STATES[i(OFF.state)] ?? 'searching';
  const found = i(OFF.found) !== 0;
  const H = [];
  for (let k = 0; k < 9; ++k) H.push(d(OFF.H + 8 * k));
  return {
    state,                                    // 'searching' | 'locked' | 'lost'
    found,                                    // this frame verified a place
    point: state === 'locked' ? [d(OFF.point), d(OFF.point + 8)] : null,  // smoothed aim, field modules
    rawPoint: found ? [d(OFF.rawPoint), d(OFF.rawPoint + 8)] : null,     // this frame's own aim point
    confidence: d(OFF.confidence),            // as the native requester's aim message
    H,                                        // image -> field, row-major
    windows: i(OFF.windows),
    usedPrior: i(OFF.usedPrior) !== 0,
    framesSinceLock: i(OFF.framesSinceLock),
    edgesFitted: i(OFF.edgesFitted),
    anotherField: i(OFF.anotherField) !== 0,  // another screen's field under the aim
    demodulated: i(OFF.demodulated) !== 0,    // the place is the pulse search's (setPulse)
    ms: d(OFF.ms),                            // inside the module, grey conversion included
    greyMs: d(OFF.greyMs),
    detectMs: d(OFF.detectMs),
    failure: found ? '' : cString(M, M._umf_failure(handle)),
  };
}
