// The web client's detector (WebAssembly, web/site/detector.js) against the
// native one on the same frames: umf_wasm_parity_frames wrote them as RGBA
// with the native Tracker's result for each; this runs the wasm Tracker over
// them in the same order and compares frame by frame.
//
//   node --no-experimental-fetch tests/web/wasm_parity.mjs PARITY_DIR SITE_DIR
//
// Must agree: the grey image (bit for bit: the same luma), the state, whether
// a place was found, the windows, whether the prior was used, the edges
// fitted; the aim point within 1e-6 modules, the homography within 1e-6
// (relative), the confidence within 1e-9. Prints the largest differences.
import fs from 'fs';
import path from 'path';
import { pathToFileURL } from 'url';

const [parityDir, siteDir] = process.argv.slice(2);
if (!parityDir || !siteDir) {
  console.error('usage: wasm_parity.mjs PARITY_DIR SITE_DIR');
  process.exit(2);
}
const { createDetector } = await import(pathToFileURL(path.join(siteDir, 'detector.js')).href);

const POINT_TOL = 1e-6, H_TOL = 1e-6, CONF_TOL = 1e-9;

function fnv1a(bytes) {
  let h = 2166136261;
  for (let i = 0; i < bytes.length; ++i) h = Math.imul(h ^ bytes[i], 16777619) >>> 0;
  return h >>> 0;
}

const pointDiff = (a, b) => (a && b ? Math.hypot(a[0] - b[0], a[1] - b[1]) : a === b ? 0 : Infinity);
function hDiff(a, b) {
  // Both normalised to H[2][2] = 1 (the detector's own convention), then the
  // largest difference relative to the largest entry.
  const na = a.map((x) => x / a[8]), nb = b.map((x) => x / b[8]);
  const scale = Math.max(...na.map(Math.abs));
  return Math.max(...na.map((x, i) => Math.abs(x - nb[i]))) / scale;
}

const doc = JSON.parse(fs.readFileSync(path.join(parityDir, 'frames.json'), 'utf8'));
const fieldJson = fs.readFileSync(path.join(parityDir, doc.field), 'utf8');
const detector = await createDetector(fieldJson);

let failures = 0, frames = 0;
const worst = { point: 0, rawPoint: 0, H: 0, confidence: 0 };
const fail = (what) => {
  ++failures;
  console.log(`  MISMATCH ${what}`);
};
for (const seq of doc.sequences) {
  detector.reset();
  for (const [i, native] of seq.frames.entries()) {
    const rgba = fs.readFileSync(path.join(parityDir, native.file));
    const r = detector.track(new Uint8Array(rgba.buffer, rgba.byteOffset, rgba.byteLength), seq.width, seq.height,
                             { format: 'rgba' });
    ++frames;
    const tag = `${seq.name} frame ${i}`;
    const grey = fnv1a(detector.grey(seq.width, seq.height));
    const dPoint = pointDiff(r.point, native.point), dRaw = pointDiff(r.rawPoint, native.raw_point);
    const dH = native.found && r.found ? hDiff(r.H, native.H) : 0;
    const dConf = Math.abs(r.confidence - native.confidence);
    console.log(`${tag}: ${r.state} (native ${native.state}), windows ${r.windows} (${native.windows}), ` +
                `point diff ${dPoint.toExponential(2)}, H diff ${dH.toExponential(2)}, ${r.ms.toFixed(2)} ms` +
                (r.found ? '' : ` [${r.failure}]`));
    if (grey !== native.grey_fnv1a) fail(`${tag}: grey image hash ${grey} != native ${native.grey_fnv1a}`);
    if (r.state !== native.state) fail(`${tag}: state ${r.state} != native ${native.state}`);
    if (r.found !== native.found) fail(`${tag}: found ${r.found} != native ${native.found}`);
    if (r.windows !== native.windows) fail(`${tag}: windows ${r.windows} != native ${native.windows}`);
    if (r.usedPrior !== native.used_prior) fail(`${tag}: used_prior ${r.usedPrior} != native ${native.used_prior}`);
    if (r.edgesFitted !== native.edges_fitted) fail(`${tag}: edges_fitted ${r.edgesFitted} != native ${native.edges_fitted}`);
    if (r.framesSinceLock !== native.frames_since_lock) fail(`${tag}: frames_since_lock differs`);
    if (!(dPoint <= POINT_TOL)) fail(`${tag}: aim point ${r.point} vs native ${native.point}`);
    if (!(dRaw <= POINT_TOL)) fail(`${tag}: raw aim point ${r.rawPoint} vs native ${native.raw_point}`);
    if (!(dH <= H_TOL)) fail(`${tag}: homography differs by ${dH}`);
    if (!(dConf <= CONF_TOL)) fail(`${tag}: confidence ${r.confidence} vs native ${native.confidence}`);
    if (Number.isFinite(dPoint)) worst.point = Math.max(worst.point, dPoint);
    if (Number.isFinite(dRaw)) worst.rawPoint = Math.max(worst.rawPoint, dRaw);
    worst.H = Math.max(worst.H, dH);
    worst.confidence = Math.max(worst.confidence, dConf);
  }
}
// Grey input (format 'grey') gives what the same frame gave as RGBA.
{
  const seq = doc.sequences[0], native = seq.frames[0];
  const rgba = fs.readFileSync(path.join(parityDir, native.file));
  detector.reset();
  detector.track(new Uint8Array(rgba), seq.width, seq.height);
  const grey = detector.grey(seq.width, seq.height);
  detector.reset();
  const r = detector.track(grey, seq.width, seq.height, { format: 'grey' });
  if (r.state !== native.state || !(pointDiff(r.point, native.point) <= POINT_TOL))
    fail(`grey input: ${r.state} ${r.point} vs native ${native.state} ${native.point}`);
}
// A camera's frame rate spreads the tracker's search over the frames without
// a lock; back at 0 (a photo's search) the tracker gives what the native one
// gave on the same frame. Bad rates are refused with a message.
{
  const seq = doc.sequences[0];
  const native = seq.frames[0];
  const rgba = fs.readFileSync(path.join(parityDir, native.file));
  detector.setFrameRate(30);
  const spread = detector.track(new Uint8Array(rgba), seq.width, seq.height);
  detector.setFrameRate(0);
  const r = detector.track(new Uint8Array(rgba), seq.width, seq.height);
  if (r.state !== native.state || !(pointDiff(r.point, native.point) <= POINT_TOL))
    fail(`first frame at frame rate 0 again: ${r.state} ${r.point} vs native ${native.state} ${native.point}`);
  console.log(`first frame at 30 frames a second: ${spread.state}, ${spread.ms.toFixed(2)} ms; at 0: ${r.state}, ` +
              `${r.ms.toFixed(2)} ms`);
  for (const bad of [-1, NaN, Infinity]) {
    let refused = false;
    try {
      detector.setFrameRate(bad);
    } catch (e) {
      refused = /rate/.test(e.message);
    }
    if (!refused) fail(`frame rate ${bad} was not refused with a message`);
  }
  detector.setFrameRate(0);
}
detector.destroy();

// Bad input must come back as an error, not abort the module.
let rejected = false;
try {
  await createDetector('{"format":"umf-field/1","width":3}');
} catch (e) {
  rejected = /field/.test(e.message);
}
if (!rejected) fail('a bad field was not rejected with a message');
const again = await createDetector(fieldJson);  // the module still works after the exception
if (again.track(new Uint8Array(64 * 48), 64, 48).state !== 'searching') fail('tracking after a rejected field');
again.destroy();

console.log(`largest differences: point ${worst.point.toExponential(2)}, raw point ${worst.rawPoint.toExponential(2)}, ` +
            `H ${worst.H.toExponential(2)} (relative), confidence ${worst.confidence.toExponential(2)}`);
console.log(failures === 0 ? `wasm parity: ok (${frames} frames)` : `wasm parity: FAILED (${failures} mismatches)`);
process.exit(failures === 0 ? 0 : 1);
