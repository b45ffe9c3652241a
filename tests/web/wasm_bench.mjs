// Speed of the web client's detector (WebAssembly under node) against the
// native build on the same frames. Not a test: numbers for docs/.
//
//   build/X/tests/web/umf_wasm_parity_frames DIR --bench 50     (native; writes DIR/native_bench.json)
//   node --no-experimental-fetch tests/web/wasm_bench.mjs DIR build/X/web/site [RUNS]
//
// The same calls as the native --bench, per frame size, RUNS times each:
//   search  reset, then one frame (full detection), frames where the field is found
//   locked  the sequence in order, frames locked after a locked frame (the tracker's follow path)
//   miss    reset, then a frame without the field (a search that finds nothing)
// Times are medians over every frame and run: "wasm" is measured inside the
// module (RGBA to grey included, as the native time includes to_luma);
// "wasm+copy" adds the JavaScript side (copying the frame in, reading the result);
// the "detector only" columns leave out the grey conversion on both sides
// (the native build converts with umf::to_luma, the wasm one with SIMD).
import fs from 'fs';
import path from 'path';
import { performance } from 'perf_hooks';
import { pathToFileURL } from 'url';

const [parityDir, siteDir, runsArg] = process.argv.slice(2);
if (!parityDir || !siteDir) {
  console.error('usage: wasm_bench.mjs PARITY_DIR SITE_DIR [RUNS]');
  process.exit(2);
}
const runs = Number(runsArg ?? 50);
const { createDetector } = await import(pathToFileURL(path.join(siteDir, 'detector.js')).href);
const doc = JSON.parse(fs.readFileSync(path.join(parityDir, 'frames.json'), 'utf8'));
const nativePath = path.join(parityDir, 'native_bench.json');
const native = fs.existsSync(nativePath) ? JSON.parse(fs.readFileSync(nativePath, 'utf8')) : null;
const detector = await createDetector(fs.readFileSync(path.join(parityDir, doc.field), 'utf8'));

const median = (v) => {
  if (!v.length) return NaN;
  const s = [...v].sort((a, b) => a - b), m = s.length >> 1;
  return s.length % 2 ? s[m] : (s[m - 1] + s[m]) / 2;
};

function measure(seq, frames) {
  const inside = { search: [], locked: [], miss: [] }, wall = { search: [], locked: [], miss: [] };
  const detect = { search: [], locked: [], miss: [] };
  const track = (px) => {
    const t0 = performance.now();
    const r = detector.track(px, seq.width, seq.height, { format: 'rgba' });
    return [r, performance.now() - t0];
  };
  for (let run = 0; run < runs; ++run) {
    for (const px of frames) {
      detector.reset();
      const [r, ms] = track(px);
      const kind = r.state === 'locked' ? 'search' : 'miss';
      inside[kind].push(r.ms);
      wall[kind].push(ms);
      detect[kind].push(r.detectMs);
    }
    detector.reset();
    frames.forEach((px, i) => {
      const [r, ms] = track(px);
      if (r.state === 'locked' && i > 0 && seq.frames[i - 1].state === 'locked') {
        inside.locked.push(r.ms);
        wall.locked.push(ms);
        detect.locked.push(r.detectMs);
      }
    });
  }
  const out = {};
  for (const k of Object.keys(inside))
    out[k] = { wasm: median(inside[k]), wall: median(wall[k]), detect: median(detect[k]), n: inside[k].length };
  return out;
}

console.log(`node ${process.version}, ${runs} runs per frame, medians in ms`);
console.log('                          per frame                     |  detector only');
console.log('size       kind    native   wasm  wasm+copy  wasm/native | native   wasm  wasm/native');
for (const seq of doc.sequences) {
  const frames = seq.frames.map((f) => new Uint8Array(fs.readFileSync(path.join(parityDir, f.file))));
  measure(seq, frames.slice(0, 3));  // warm-up: let the engine tier up the wasm code
  const m = measure(seq, frames);
  const n = native?.sequences?.[seq.name];
  for (const kind of ['search', 'locked', 'miss']) {
    const nat = (n && n[`${kind}_ms`]) ?? NaN, natDetect = (n && n[`${kind}_detect_ms`]) ?? NaN;
    const f = (x, w) => x.toFixed(2).padStart(w);
    const line = [seq.name.padEnd(10), kind.padEnd(6), f(nat, 7), f(m[kind].wasm, 6), f(m[kind].wall, 10),
                  f(m[kind].wasm / nat, 12), '|', f(natDetect, 6), f(m[kind].detect, 6), f(m[kind].detect / natDetect, 12),
                  `  (${m[kind].n} samples)`];
    console.log(line.join(' '));
  }
}
detector.destroy();
