// Speed of the web client's detector in headless Chromium (the real browser
// engine, the module as the provider serves it) against the native build on
// the same frames, and the time from page load to the first lock. Not a
// test: numbers for docs/BENCHMARKS.md.
//
//   build/X/tests/web/umf_wasm_parity_frames DIR --bench 50       (frames + native times)
//   node tests/web/browser/bench.mjs --site build/X/web/site --frames DIR [--runs 30] [--chromium PATH]
//
// The page's own origin serves the site (a route over the site folder, so the
// module and its .wasm load as they do from the provider) and the frames
// under /bench/. Per frame size it measures, as tests/web/wasm_bench.mjs does
// under node: "search" (reset, then one frame where the field is found),
// "miss" (reset, then one frame where it is not: what a page that has not
// locked yet pays per frame) and "locked" (the sequence in order, frames
// locked after a locked frame), the module's own time (RGBA to grey included)
// and the wall time with the copy in.
import fs from 'node:fs';
import path from 'node:path';
import { createRequire } from 'node:module';

const args = Object.fromEntries(process.argv.slice(2).reduce((pairs, a, i, all) =>
  (a.startsWith('--') ? [...pairs, [a.slice(2), all[i + 1]]] : pairs), []));
const site = args.site, framesDir = args.frames, runs = Number(args.runs ?? 30);
const chromiumPath = args.chromium ?? '/usr/bin/chromium';
if (!site || !framesDir) {
  console.error('usage: bench.mjs --site SITE_DIR --frames PARITY_DIR [--runs N] [--chromium PATH]');
  process.exit(2);
}
// playwright-core as the browser tests install it (tests/web/browser/npm_install.mjs).
const require = createRequire(path.resolve(args.modules ?? path.join(framesDir, '..', 'browser', 'node_modules')) + '/');
const { chromium } = require('playwright-core');

const doc = JSON.parse(fs.readFileSync(path.join(framesDir, 'frames.json'), 'utf8'));
const native = fs.existsSync(path.join(framesDir, 'native_bench.json'))
  ? JSON.parse(fs.readFileSync(path.join(framesDir, 'native_bench.json'), 'utf8')) : null;
const types = { '.js': 'text/javascript', '.wasm': 'application/wasm', '.html': 'text/html', '.json': 'application/json' };

const browser = await chromium.launch({ executablePath: chromiumPath, headless: true, args: ['--no-sandbox'] });
const page = await (await browser.newContext()).newPage();
await page.route('https://umf.bench/**', (route) => {
  const url = new URL(route.request().url());
  const file = url.pathname.startsWith('/bench/')
    ? path.join(framesDir, path.basename(url.pathname))
    : path.join(site, url.pathname === '/' ? 'blank.html' : path.basename(url.pathname));
  if (url.pathname === '/') return route.fulfill({ body: '<!doctype html><title>bench</title>', contentType: 'text/html' });
  if (!fs.existsSync(file)) return route.fulfill({ status: 404, body: '' });
  route.fulfill({ body: fs.readFileSync(file), contentType: types[path.extname(file)] ?? 'application/octet-stream' });
});
await page.goto('https://umf.bench/');
const version = browser.version();

const results = await page.evaluate(async ({ doc, runs }) => {
  const { createDetector } = await import('/detector.js');
  const field = await (await fetch(`/bench/${doc.field}`)).text();
  const detector = await createDetector(field);
  const median = (v) => {
    if (!v.length) return null;
    const s = [...v].sort((a, b) => a - b), m = s.length >> 1;
    return s.length % 2 ? s[m] : (s[m - 1] + s[m]) / 2;
  };
  const out = {};
  for (const seq of doc.sequences) {
    const frames = [];
    for (const f of seq.frames) frames.push(new Uint8Array(await (await fetch(`/bench/${f.file}`)).arrayBuffer()));
    const m = { search: [], miss: [], locked: [], searchWall: [], missWall: [], lockedWall: [] };
    const measure = (record) => {
      for (let run = 0; run < runs; ++run) {
        for (const px of frames) {
          detector.reset();
          const t0 = performance.now();
          const r = detector.track(px, seq.width, seq.height, { format: 'rgba' });
          const kind = r.state === 'locked' ? 'search' : 'miss';
          if (record) { m[kind].push(r.ms); m[`${kind}Wall`].push(performance.now() - t0); }
        }
        detector.reset();
        let previous = null;
        for (const px of frames) {
          const t0 = performance.now();
          const r = detector.track(px, seq.width, seq.height, { format: 'rgba' });
          if (record && r.state === 'locked' && previous === 'locked') { m.locked.push(r.ms); m.lockedWall.push(performance.now() - t0); }
          previous = r.state;
        }
      }
    };
    measure(false);  // warm-up: the engine tiers the code up
    measure(true);
    out[seq.name] = { search: median(m.search), miss: median(m.miss), locked: median(m.locked),
                      searchWall: median(m.searchWall), missWall: median(m.missWall), lockedWall: median(m.lockedWall),
                      n: m.search.length + m.miss.length + m.locked.length };
  }
  detector.destroy();
  return out;
}, { doc, runs });
await browser.close();

console.log(`Chromium ${version}, ${runs} runs per frame, medians in ms (module time; wall time with the copy in)`);
console.log('| size | kind | native | Chromium wasm | wall | wasm / native |');
console.log('|---|---|---|---|---|---|');
for (const [name, r] of Object.entries(results)) {
  const n = native?.sequences?.[name];
  for (const kind of ['search', 'miss', 'locked']) {
    if (r[kind] === null) continue;  // no frame of that kind in this sequence
    const nat = n?.[`${kind}_ms`] ?? NaN;
    console.log(`| ${name} | ${kind} | ${nat.toFixed(2)} | ${r[kind].toFixed(2)} | ${r[`${kind}Wall`].toFixed(2)} | ${(r[kind] / nat).toFixed(2)} |`);
  }
}
