// The web client's pulse search (WebAssembly) against the native one, on the
// frames umf_wasm_pulse_frames wrote: a field pulsing at 0.01..0.04 that no
// single frame shows. The detector is told the pulse as the page tells it
// (setPulse from the welcome's overlay) and each frame's time (timeMs).
//
//   node --no-experimental-fetch tests/web/wasm_pulse.mjs PULSE_DIR SITE_DIR
//
// Must agree frame by frame with the native PulseTracker: the state and
// whether the place was demodulated; the aim point within a quarter of a
// module (the refit on a demodulated image follows the float rounding, which
// differs between the two builds: 0.24 module apart at most here, frames
// 28-33, since a carried place is followed at half size first; a tenth
// before; both builds within 0.3 module of the truth there).
// Must lock on the demodulated pulse within the frames, and every place
// locked must be within half a module of the truth. Prints the median ms of
// an update, native and wasm, and the wasm's again with the tracker's search
// held to a 30 fps camera's share (setFrameRate(30), as the page runs it).
import fs from 'fs';
import path from 'path';
import { pathToFileURL } from 'url';

const [dir, siteDir] = process.argv.slice(2);
if (!dir || !siteDir) {
  console.error('usage: wasm_pulse.mjs PULSE_DIR SITE_DIR');
  process.exit(2);
}
const { createDetector } = await import(pathToFileURL(path.join(siteDir, 'detector.js')).href);
const POINT_TOL = 0.25, RIGHT = 0.5;

const doc = JSON.parse(fs.readFileSync(path.join(dir, 'pulse.json'), 'utf8'));
const detector = await createDetector(fs.readFileSync(path.join(dir, doc.field), 'utf8'));
detector.setPulse(doc.pulse.waveform, doc.pulse.period_s, { min: doc.pulse.opacity_min, max: doc.pulse.opacity_max });

let failures = 0;
const fail = (what) => {
  ++failures;
  console.log(`  MISMATCH ${what}`);
};
const dist = (a, b) => Math.hypot(a[0] - b[0], a[1] - b[1]);
let firstLock = -1, demodulated = 0, worstPoint = 0;
const nativeMs = [], wasmMs = [];
for (const [i, native] of doc.frames.entries()) {
  const rgba = fs.readFileSync(path.join(dir, native.file));
  const r = detector.track(new Uint8Array(rgba.buffer, rgba.byteOffset, rgba.byteLength), doc.width, doc.height,
                           { format: 'rgba', timeMs: native.time_ms });
  nativeMs.push(native.ms);
  wasmMs.push(r.ms);
  const tag = `frame ${i}`;
  if (r.state !== native.state) fail(`${tag}: state ${r.state}, native ${native.state}`);
  if (r.demodulated !== native.demodulated) fail(`${tag}: demodulated ${r.demodulated}, native ${native.demodulated}`);
  if (r.state === 'locked' && native.point) {
    const d = dist(r.point, native.point);
    worstPoint = Math.max(worstPoint, d);
    if (!(d <= POINT_TOL)) fail(`${tag}: point ${r.point}, native ${native.point} (${d})`);
    if (!(dist(r.point, native.truth) < RIGHT)) fail(`${tag}: point ${r.point} is ${dist(r.point, native.truth)} modules from the truth`);
    if (firstLock < 0) firstLock = i;
  }
  if (r.demodulated) ++demodulated;
}
const median = (v) => {
  const s = [...v].sort((a, b) => a - b);
  return s.length ? s[Math.floor(s.length / 2)] : NaN;
};
console.log(`${doc.frames.length} frames: first lock at frame ${firstLock}, ${demodulated} demodulated; ` +
            `largest point difference ${worstPoint.toExponential(2)} modules; update ms median native ` +
            `${median(nativeMs).toFixed(1)}, wasm ${median(wasmMs).toFixed(1)}`);
if (demodulated === 0) fail('no frame locked on the demodulated pulse');
// As the page runs it: the camera's rate set, the pulse kept.
detector.setFrameRate(30);
const pagedMs = [];
let pagedLocks = 0;
for (const native of doc.frames) {
  const rgba = fs.readFileSync(path.join(dir, native.file));
  const r = detector.track(new Uint8Array(rgba.buffer, rgba.byteOffset, rgba.byteLength), doc.width, doc.height,
                           { format: 'rgba', timeMs: native.time_ms });
  pagedMs.push(r.ms);
  if (r.state === 'locked') ++pagedLocks;
}
console.log(`at 30 fps (the tracker's search held to its share): ${pagedLocks} frames locked, update ms median ` +
            `${median(pagedMs).toFixed(1)}, largest ${Math.max(...pagedMs).toFixed(1)}`);
detector.destroy();
if (failures) {
  console.log(`FAIL: ${failures} mismatches`);
  process.exit(1);
}
console.log('OK');
