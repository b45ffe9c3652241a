// The phone page in headless Chromium, one scenario per run (the CTest tests
// web.browser.*; tests/web/browser/README.md has the page contract it checks).
//
//   node run.mjs --scenario NAME --provider BIN --site DIR --board BOARD.json
//                --fixtures DIR --modules DIR [--chromium PATH] [--headed] [--keep]
//
// --site      the phone page's folder (build/.../web/site), served by the
//             provider with --web; without index.html the scenario skips
// --fixtures  where web.browser.video_* wrote tile0.y4m, tile1.y4m, tile2.png
// --modules   the node_modules that web.browser.npm_install filled
// Scenarios: camera_file, camera_url_http, photo, wrong_token, unreachable,
// camera_denied, no_camera, websocket_blocked, detection_failing, insecure_photo,
// unpaired. Exit codes: 0 passed, 1 failed, 77 skipped (the page,
// Chromium, playwright-core or a fixture is missing), 2 usage.
import { spawn } from 'node:child_process';
import crypto from 'node:crypto';
import fs from 'node:fs';
import { createRequire } from 'node:module';
import net from 'node:net';
import os from 'node:os';
import path from 'node:path';

const SKIP = 77;
const STATES = ['unpaired', 'connecting', 'camera', 'searching', 'locked', 'grabbing', 'result', 'photo', 'error'];

// ---------------------------------------------------------------- options
const opts = { chromium: '/usr/bin/chromium', headed: false, keep: false };
{
  const argv = process.argv.slice(2);
  for (let i = 0; i < argv.length; ++i) {
    const a = argv[i];
    if (a === '--headed') opts.headed = true;
    else if (a === '--keep') opts.keep = true;
    else if (a.startsWith('--') && i + 1 < argv.length) opts[a.slice(2)] = argv[++i];
    else usage(`unexpected argument ${a}`);
  }
  for (const k of ['scenario', 'provider', 'site', 'board', 'fixtures', 'modules']) if (!opts[k]) usage(`--${k} is needed`);
}
function usage(message) {
  console.error(`run.mjs: ${message}\nusage: node run.mjs --scenario NAME --provider BIN --site DIR --board BOARD.json ` +
                '--fixtures DIR --modules DIR [--chromium PATH] [--headed] [--keep]');
  process.exit(2);
}

const t0 = Date.now();
const log = (...a) => console.log(`[${((Date.now() - t0) / 1000).toFixed(2).padStart(6)} s]`, ...a);
function skip(why) {
  console.log(`SKIP: ${why}`);
  process.exit(SKIP);
}
class Failure extends Error {}
// A skip found while a scenario runs: thrown, so the provider and Chromium are stopped first.
class Skip extends Error {}
const check = (ok, message) => {
  if (!ok) throw new Failure(message);
  log(`ok: ${message}`);
};

// ---------------------------------------------------------------- what is needed
if (!fs.existsSync(path.join(opts.site, 'index.html')))
  skip(`the phone page is not built yet (no ${path.join(opts.site, 'index.html')}); ` +
       'these tests run once web/ produces it');
if (!fs.existsSync(opts.chromium)) skip(`no Chromium at ${opts.chromium} (scripts/install-deps.sh installs it)`);
let chromium;
try {
  chromium = createRequire(path.join(path.resolve(opts.modules), 'noop.js'))('playwright-core').chromium;
} catch (e) {
  skip(`playwright-core is not installed in ${opts.modules} (the test web.browser.npm_install installs it): ${e.message}`);
}
const SCENARIOS = ['camera_file', 'camera_url_http', 'photo', 'wrong_token', 'unreachable', 'camera_denied', 'no_camera',
                   'websocket_blocked', 'detection_failing', 'insecure_photo', 'unpaired'];
if (!SCENARIOS.includes(opts.scenario)) usage(`no scenario ${opts.scenario}; there are ${SCENARIOS.join(', ')}`);
const boardFile = path.resolve(opts.board);
const board = JSON.parse(fs.readFileSync(boardFile, 'utf8'));
const item = (i) => {
  const it = board.items[i];
  const out = { ...it };
  if (it.file) {
    out.path = path.resolve(path.dirname(boardFile), it.file);
    const bytes = fs.readFileSync(out.path);
    out.size = bytes.length;
    out.sha256 = crypto.createHash('sha256').update(bytes).digest('hex');
    out.name = path.basename(out.path);
  }
  return out;
};
const fixture = (name) => {
  const p = path.join(opts.fixtures, name);
  if (!fs.existsSync(p)) throw new Skip(`the fixture ${p} is missing (made by the tests web.browser.video_* / photo_still)`);
  return p;
};

// ---------------------------------------------------------------- the provider
// What a failure report shows: the page, its console, the provider's output.
const current = { page: null, consoleLines: [], provider: null };
const work = fs.mkdtempSync(path.join(os.tmpdir(), `umf-browser-${opts.scenario}-`));
const cleanups = [];

async function startProvider() {
  const args = ['serve', '--headless', '--board', boardFile, '--screen', '1920x1080', '--port', '0',
                '--bind', '127.0.0.1', '--config-dir', path.join(work, 'config'), '--no-qr', '--web', opts.site];
  const child = spawn(opts.provider, args, { stdio: ['ignore', 'pipe', 'pipe'],
                                             env: { ...process.env, XDG_RUNTIME_DIR: work } });
  let out = '';
  child.stderr.on('data', (d) => { out += d; });
  const stopped = new Promise((resolve) => child.on('exit', (code, signal) => resolve({ code, signal })));
  cleanups.push(async () => {
    if (child.exitCode === null && child.signalCode === null) child.kill('SIGTERM');
    const timer = setTimeout(() => child.kill('SIGKILL'), 5000);
    await stopped;
    clearTimeout(timer);
  });
  const found = await new Promise((resolve) => {
    let base = null;
    const timer = setTimeout(() => resolve(null), 20000);
    child.stdout.on('data', (d) => {
      out += d;
      const listening = /listening on (https:\/\/\S+?:\d+)/.exec(out);
      const pairing = /^pairing URL: (\S+)$/m.exec(out);
      if (listening) base = listening[1];
      if (base && pairing) {
        clearTimeout(timer);
        resolve({ base, pairing: pairing[1] });
      }
    });
    child.on('exit', () => resolve(null));
    child.on('error', (e) => { out += `\ncannot start ${opts.provider}: ${e.message}`; resolve(null); });
  });
  if (!found) throw new Failure(`the provider printed no pairing URL:\n${out}`);
  current.provider = () => out;
  log(`provider on ${found.base}, pairing URL ${found.pairing.replace(/t=[^&]+/, 't=…')}`);
  return { ...found, output: () => out };
}

// The pairing URL with test options in the query, before the fragment.
function pageUrl(pairing, query) {
  const u = new URL(pairing);
  for (const [k, v] of Object.entries(query)) u.searchParams.set(k, v);
  return u.toString();
}

// ---------------------------------------------------------------- the browser
async function launch({ video, fakeUi = true, fakeDevice = true } = {}) {
  const args = ['--ignore-certificate-errors', '--autoplay-policy=no-user-gesture-required'];
  if (fakeDevice) args.push('--use-fake-device-for-media-stream');
  if (fakeUi) args.push('--use-fake-ui-for-media-stream');
  if (video) args.push(`--use-file-for-fake-video-capture=${video}`);
  if (process.getuid?.() === 0) args.push('--no-sandbox');  // Chromium's sandbox refuses root
  const started = Date.now();
  const browser = await chromium.launch({ executablePath: opts.chromium, headless: !opts.headed, args, timeout: 30000,
                                         handleSIGINT: false, handleSIGTERM: false, handleSIGHUP: false });
  cleanups.push(() => browser.close().catch(() => {}));
  log(`Chromium ${browser.version()} started in ${Date.now() - started} ms (${args.join(' ')})`);
  return browser;
}

async function openPage(browser, url, { permissions, route } = {}) {
  const context = await browser.newContext({ ignoreHTTPSErrors: true, viewport: { width: 412, height: 915 },
                                             isMobile: false, hasTouch: true });
  if (permissions) await context.grantPermissions(permissions.grant ?? [], permissions.origin ? { origin: permissions.origin } : {});
  if (route) await context.route('**/*', route);
  // Every change of body[data-state], with the time since navigation started.
  await context.addInitScript(() => {
    window.__umfStates = [];
    const note = () => {
      const s = document.body?.dataset.state;
      const last = window.__umfStates[window.__umfStates.length - 1];
      if (s && (!last || last[1] !== s)) window.__umfStates.push([Math.round(performance.now()), s]);
    };
    new MutationObserver(note).observe(document, { subtree: true, attributes: true, attributeFilter: ['data-state'], childList: true });
  });
  const page = await context.newPage();
  const consoleLines = [];
  page.on('console', (m) => consoleLines.push(`${m.type()}: ${m.text()}`));
  page.on('pageerror', (e) => consoleLines.push(`pageerror: ${e.message}`));
  page.on('crash', () => consoleLines.push('page crashed'));
  current.page = page;
  current.consoleLines = consoleLines;
  const started = Date.now();
  await page.goto(url, { waitUntil: 'load', timeout: 20000 });
  log(`page loaded in ${Date.now() - started} ms: ${url.replace(/t=[^&]+/, 't=…')}`);
  return page;
}

const stateOf = (page) => page.evaluate(() => document.body?.dataset.state ?? null);
const statesSeen = (page) => page.evaluate(() => (window.__umfStates ?? []).map(([t, s]) => `${s}@${t}ms`).join(' → '));
const debugOf = (page) => page.evaluate(() => {
  const d = window.umfDebug;
  return d ? JSON.parse(JSON.stringify(d)) : null;
});

// Waits for one of `wanted` states; fails at once on an unexpected error state.
async function waitForState(page, wanted, timeoutMs, { onState } = {}) {
  const deadline = Date.now() + timeoutMs;
  let last = null;
  while (Date.now() < deadline) {
    const s = await stateOf(page);
    if (s !== last) {
      if (s !== null && !STATES.includes(s)) throw new Failure(`body[data-state] is "${s}", not one of the contract's states`);
      last = s;
      if (onState) await onState(s);
    }
    if (wanted.includes(s)) return s;
    if (s === 'error') {
      const e = await page.evaluate(() => {
        const el = document.querySelector('#error');
        return el ? { code: el.dataset.code, text: el.textContent.trim() } : null;
      });
      throw new Failure(`the page went to state error (${JSON.stringify(e)}) while waiting for ${wanted.join('|')}`);
    }
    await page.waitForTimeout(50);
  }
  throw new Failure(`state ${wanted.join('|')} not reached within ${timeoutMs} ms (state: ${last})`);
}

async function resultOf(page) {
  return page.evaluate(() => {
    const r = document.querySelector('#result');
    if (!r) return null;
    const style = getComputedStyle(r);
    return { ...r.dataset, visible: !r.hidden && style.display !== 'none' && style.visibility !== 'hidden' };
  });
}

async function waitForVerified(page, timeoutMs) {
  try {
    await page.waitForSelector('#result[data-verified="true"]', { state: 'attached', timeout: timeoutMs });
    return true;
  } catch {
    return false;
  }
}

async function errorOf(page, timeoutMs) {
  await waitForState(page, ['error'], timeoutMs).catch((e) => {
    if (!(e instanceof Failure) || !/went to state error/.test(e.message)) throw e;
  });
  return page.evaluate(() => {
    const e = document.querySelector('#error');
    return e ? { code: e.dataset.code, text: e.textContent.trim(), visible: !e.hidden && getComputedStyle(e).display !== 'none' } : null;
  });
}

// ---------------------------------------------------------------- checks shared by the grabs
async function checkFileResult(page, expected) {
  const r = await resultOf(page);
  log(`#result: ${JSON.stringify(r)}`);
  check(r && r.visible, '#result is visible');
  check(r.kind === 'file', `data-kind is file (${r.kind})`);
  check(r.title === expected.title, `data-title is "${expected.title}" (${r.title})`);
  check(r.name === expected.name, `data-name is ${expected.name} (${r.name})`);
  check(Number(r.size) === expected.size, `data-size is ${expected.size} (${r.size})`);
  check(r.sha256 === expected.sha256, `data-sha256 is the file's (${r.sha256})`);
  check(await waitForVerified(page, 10000), 'data-verified="true": the downloaded bytes matched the SHA-256');
}

async function reportTiming(page, loadStart) {
  const d = await debugOf(page);
  log(`umfDebug: ${JSON.stringify({ ...d, lastResult: d?.lastResult ? '…' : d?.lastResult })}`);
  if (d && typeof d.firstLockMs === 'number')
    console.log(`TIMING first lock: ${Math.round(d.firstLockMs)} ms after page load (${d.frames} frames, ${d.locks} locks, ` +
                `${d.transport}; grab done ${Date.now() - loadStart} ms after navigation started)`);
  return d;
}

// ---------------------------------------------------------------- scenarios
const scenarios = {
  // (a) The camera film of a file tile, grabbed as soon as the lock holds.
  async camera_file() {
    const expected = item(0);
    const video = fixture('tile0.y4m');
    const provider = await startProvider();
    const browser = await launch({ video });
    const loadStart = Date.now();
    const page = await openPage(browser, pageUrl(provider.pairing, { autograb: '1' }));
    await waitForState(page, ['result'], 45000);
    log(`states: ${await statesSeen(page)}`);
    await checkFileResult(page, expected);
    // And at the provider: the page's client name and the grab on its console.
    check(/requester \d+ connected: umf-web\//.test(provider.output()), 'the provider saw the page connect');
    check(provider.output().includes(`took "${expected.title}" (file ${expected.name}, ${expected.size} bytes)`),
          `the provider says the file "${expected.title}" was taken`);
    const d = await reportTiming(page, loadStart);
    check(d && (d.transport === 'ws' || d.transport === 'http'), `umfDebug.transport is set (${d?.transport})`);
    check(typeof d.firstLockMs === 'number' && d.locks > 0, 'umfDebug counted a lock and its time');
  },

  // (b) The film of a URL tile over the HTTPS transport.
  async camera_url_http() {
    const expected = item(1);
    const provider = await startProvider();
    const browser = await launch({ video: fixture('tile1.y4m') });
    const loadStart = Date.now();
    const page = await openPage(browser, pageUrl(provider.pairing, { autograb: '1', transport: 'http' }));
    await waitForState(page, ['result'], 45000);
    log(`states: ${await statesSeen(page)}`);
    const r = await resultOf(page);
    log(`#result: ${JSON.stringify(r)}`);
    check(r && r.visible, '#result is visible');
    check(r.kind === 'url', `data-kind is url (${r.kind})`);
    check(r.title === expected.title, `data-title is "${expected.title}" (${r.title})`);
    check(r.url === expected.url, `data-url is ${expected.url} (${r.url})`);
    check(new URL(page.url()).host === new URL(provider.base).host, 'the page stayed on the provider (no navigation to the URL)');
    check(provider.output().includes(`took "${expected.title}" (url)`), `the provider says the link "${expected.title}" was taken`);
    const d = await reportTiming(page, loadStart);
    check(d && d.transport === 'http', `umfDebug.transport is http (${d?.transport})`);
  },

  // (c) Photo mode: a single photograph given to #photo-input.
  async photo() {
    const expected = item(2);
    const still = fixture('tile2.png');
    const provider = await startProvider();
    const browser = await launch();
    const page = await openPage(browser, pageUrl(provider.pairing, { photo: '1', autograb: '1' }));
    await waitForState(page, ['photo'], 20000);
    const input = await page.$('#photo-input');
    check(input !== null, '#photo-input exists in photo mode');
    const attrs = await input.evaluate((e) => ({ tag: e.tagName, type: e.type, accept: e.accept, capture: e.getAttribute('capture') }));
    check(attrs.tag === 'INPUT' && attrs.type === 'file' && attrs.accept === 'image/*' && attrs.capture === 'environment',
          `#photo-input is <input type=file accept="image/*" capture="environment"> (${JSON.stringify(attrs)})`);
    await input.setInputFiles(still);
    log(`set ${still} on #photo-input`);
    // With autograb the page grabs by itself; should it stop at "locked",
    // the test taps Grab, as a user would.
    let lockedSince = null;
    const deadline = Date.now() + 30000;
    for (;;) {
      const s = await waitForState(page, ['result', 'locked'], Math.max(1, deadline - Date.now()));
      if (s === 'result') break;
      lockedSince ??= Date.now();
      if (Date.now() - lockedSince > 2000) {
        log('still locked after 2 s: tapping #grab');
        await page.click('#grab', { timeout: 5000 });
        lockedSince = Date.now() + 1e9;
      }
      await page.waitForTimeout(100);
    }
    log(`states: ${await statesSeen(page)}`);
    await checkFileResult(page, expected);
  },

  // (d) A wrong token in the fragment.
  async wrong_token() {
    const provider = await startProvider();
    const browser = await launch({ video: fixture('tile0.y4m') });
    const u = new URL(pageUrl(provider.pairing, {}));
    const fragment = new URLSearchParams(u.hash.slice(1));
    const token = fragment.get('t');
    check(token && token.length >= 22, 'the pairing URL carries a token');
    // Same length and alphabet, every character different.
    const alphabet = 'ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789-_';
    fragment.set('t', [...token].map((c) => alphabet[(alphabet.indexOf(c) + 7) % alphabet.length]).join(''));
    u.hash = fragment.toString();
    const page = await openPage(browser, u.toString());
    const e = await errorOf(page, 20000);
    log(`states: ${await statesSeen(page)}; #error: ${JSON.stringify(e)}`);
    check(e && e.code === 'token-rejected', `#error[data-code=token-rejected] (${e?.code})`);
    check(e.visible && e.text.length > 0, '#error is visible and says why');
  },

  // (e) Nothing listening: the page's own files come from disk (as from a
  // browser's cache), every other request to the origin is refused, and the
  // WebSocket meets a closed port.
  async unreachable() {
    const port = await closedPort();
    const browser = await launch({ video: fixture('tile0.y4m') });
    const origin = `https://127.0.0.1:${port}`;
    const fp = 'ab'.repeat(32);
    const url = `${origin}/?autograb=1#t=${'Q'.repeat(22)}&fp=${fp}`;
    const site = path.resolve(opts.site);
    const route = async (r) => {
      const u = new URL(r.request().url());
      const file = path.join(site, decodeURIComponent(u.pathname === '/' ? '/index.html' : u.pathname));
      if (u.origin === origin && r.request().method() === 'GET' && file.startsWith(site + path.sep) &&
          fs.existsSync(file) && fs.statSync(file).isFile())
        return r.fulfill({ path: file, headers: { 'content-type': mime(file), 'cache-control': 'no-store' } });
      return r.abort('connectionrefused');
    };
    const page = await openPage(browser, url, { route });
    const e = await errorOf(page, 30000);
    log(`states: ${await statesSeen(page)}; #error: ${JSON.stringify(e)}`);
    check(e && e.code === 'unreachable', `#error[data-code=unreachable] (${e?.code})`);
    check(e.visible && e.text.length > 0, '#error is visible and says why');
  },

  // (f) The camera refused: no fake UI accepting the prompt, and no permission granted.
  async camera_denied() {
    const provider = await startProvider();
    const browser = await launch({ video: fixture('tile0.y4m'), fakeUi: false });
    const page = await openPage(browser, pageUrl(provider.pairing, { autograb: '1' }), { permissions: { grant: [] } });
    const e = await errorOf(page, 30000);
    log(`states: ${await statesSeen(page)}; #error: ${JSON.stringify(e)}`);
    check(e && e.code === 'camera-denied', `#error[data-code=camera-denied] (${e?.code})`);
    check(e.visible && e.text.length > 0, '#error is visible and says why');
  },

  // (g) No camera at all: headless Chromium without the fake device has none.
  async no_camera() {
    const provider = await startProvider();
    const browser = await launch({ fakeDevice: false });
    const page = await openPage(browser, pageUrl(provider.pairing, { autograb: '1' }));
    const e = await errorOf(page, 30000);
    log(`states: ${await statesSeen(page)}; #error: ${JSON.stringify(e)}`);
    check(e && e.code === 'no-camera', `#error[data-code=no-camera] (${e?.code})`);
    check(e.visible && e.text.length > 0, '#error is visible and says why');
  },

  // The page opened without a pairing (no fragment, nothing kept): it says
  // to scan the QR code and connects to nothing.
  async unpaired() {
    const provider = await startProvider();
    const browser = await launch({ video: fixture('tile0.y4m') });
    const page = await openPage(browser, `${provider.base}/`);
    await waitForState(page, ['unpaired'], 20000);
    const e = await page.evaluate(() => {
      const el = document.querySelector('#error');
      return el ? { code: el.dataset.code, text: el.textContent.trim() } : null;
    });
    log(`states: ${await statesSeen(page)}; #error: ${JSON.stringify(e)}`);
    check(e && e.code === 'unpaired', `#error[data-code=unpaired] (${e?.code})`);
    check(/QR code/.test(e.text), 'it says to scan the QR code');
    check((await stateOf(page)) === 'unpaired', 'body[data-state] is unpaired');
    check(!/requester \d+ connected/.test(provider.output()), 'the page did not connect without a pairing');
  },

  // (h) The WebSocket refused (as iOS Safari does with a self-signed
  // certificate): the page falls back to HTTPS requests by itself.
  async websocket_blocked() {
    const expected = item(0);
    const provider = await startProvider();
    const browser = await launch({ video: fixture('tile0.y4m') });
    const context = await browser.newContext({ ignoreHTTPSErrors: true, viewport: { width: 412, height: 915 } });
    let refused = 0;
    await context.routeWebSocket(/\/ws$/, (ws) => {
      refused += 1;
      ws.close({ code: 1006 });
    });
    const page = await context.newPage();
    current.page = page;
    page.on('console', (m) => current.consoleLines.push(`${m.type()}: ${m.text()}`));
    await page.goto(pageUrl(provider.pairing, { autograb: '1' }));
    await waitForState(page, ['result'], 45000);
    check(refused > 0, `the page tried the WebSocket first (${refused} refused)`);
    await checkFileResult(page, expected);
    const d = await debugOf(page);
    check(d && d.transport === 'http', `it fell back to HTTPS requests (umfDebug.transport ${d?.transport})`);
  },

  // (i) A camera that never sees the field (Chromium's own test pattern):
  // the page stays searching and says how to help the detector.
  async detection_failing() {
    const provider = await startProvider();
    const browser = await launch();
    const page = await openPage(browser, pageUrl(provider.pairing, {}));
    await waitForState(page, ['searching'], 20000);
    const h = await page.waitForFunction(() => {
      const e = document.querySelector('#hint');
      return e && !e.hidden && e.dataset.code ? { code: e.dataset.code, text: e.textContent } : null;
    }, null, { timeout: 15000 }).then((handle) => handle.jsonValue()).catch(() => null);
    log(`states: ${await statesSeen(page)}; #hint: ${JSON.stringify(h)}`);
    check(h && h.code === 'detection-failing', `#hint[data-code=detection-failing] (${h?.code})`);
    check(/closer|still|light/.test(h.text), `the hint says what to do ("${h.text}")`);
    check((await stateOf(page)) === 'searching', 'the page keeps searching meanwhile');
  },

  // (j) An insecure context (plain http, where browsers allow no live
  // camera): the page offers photo mode and grabs through HTTPS requests.
  // The page is served at http://umf-insecure.test/ by a route that passes
  // every request on to the provider.
  async insecure_photo() {
    const expected = item(2);
    const still = fixture('tile2.png');
    const provider = await startProvider();
    const browser = await launch();
    const origin = 'http://umf-insecure.test';
    const route = async (r) => {
      const u = new URL(r.request().url());
      if (u.origin !== origin) return r.abort('connectionrefused');
      try {
        const response = await r.fetch({ url: provider.base + u.pathname + u.search });
        await r.fulfill({ response });
      } catch {
        // The page went away (the test ended) while a poll was passed on.
      }
    };
    const u = new URL(pageUrl(provider.pairing, { autograb: '1' }));
    const page = await openPage(browser, `${origin}/${u.search}${u.hash}`, { route });
    await waitForState(page, ['photo'], 20000);
    check(!(await page.evaluate(() => window.isSecureContext)), 'the page is not a secure context');
    const h = await page.evaluate(() => document.querySelector('#hint')?.dataset.code ?? null);
    check(h === 'insecure-context', `#hint says why there is no live camera (${h})`);
    await page.setInputFiles('#photo-input', still);
    await waitForState(page, ['result'], 30000);
    log(`states: ${await statesSeen(page)}`);
    await checkFileResult(page, expected);
  },
};

async function diagnose() {
  const page = current.page;
  if (page && !page.isClosed()) {
    try {
      console.log(`  state: ${await stateOf(page)}; states seen: ${await statesSeen(page)}`);
      console.log(`  umfDebug: ${JSON.stringify(await debugOf(page))}`);
      console.log(`  #error: ${JSON.stringify(await page.evaluate(() => {
        const e = document.querySelector('#error');
        return e ? { code: e.dataset.code, text: e.textContent.trim() } : null;
      }))}`);
      const shot = path.join(opts.fixtures, `failure-${opts.scenario}.png`);
      await page.screenshot({ path: shot, timeout: 5000 });
      console.log(`  screenshot: ${shot}`);
    } catch (e) {
      console.log(`  (the page could not be inspected: ${e.message})`);
    }
  }
  if (current.consoleLines.length) console.log(`  page console:\n    ${current.consoleLines.slice(-40).join('\n    ')}`);
  if (current.provider) console.log(`  provider output:\n    ${current.provider().trim().split('\n').slice(-30).join('\n    ')}`);
}

function mime(file) {
  const types = { '.html': 'text/html; charset=utf-8', '.js': 'text/javascript', '.mjs': 'text/javascript',
                  '.wasm': 'application/wasm', '.css': 'text/css', '.json': 'application/json', '.svg': 'image/svg+xml',
                  '.png': 'image/png', '.webmanifest': 'application/manifest+json', '.ico': 'image/x-icon' };
  return types[path.extname(file)] ?? 'application/octet-stream';
}

// A port that nothing listens on: bound, then released.
function closedPort() {
  return new Promise((resolve, reject) => {
    const s = net.createServer();
    s.on('error', reject);
    s.listen(0, '127.0.0.1', () => {
      const { port } = s.address();
      s.close(() => resolve(port));
    });
  });
}

// ---------------------------------------------------------------- main
const scenario = scenarios[opts.scenario];
let exitCode = 0;
// CTest's timeout ends the runner with SIGTERM: stop the provider and Chromium too.
for (const signal of ['SIGTERM', 'SIGINT', 'SIGHUP']) {
  process.on(signal, async () => {
    console.log(`FAIL ${opts.scenario}: ${signal} (timed out?)`);
    await diagnose().catch(() => {});
    for (const c of cleanups.reverse()) await c().catch(() => {});
    if (!opts.keep) fs.rmSync(work, { recursive: true, force: true });
    process.exit(1);
  });
}
try {
  log(`scenario ${opts.scenario}`);
  fs.rmSync(path.join(opts.fixtures, `failure-${opts.scenario}.png`), { force: true });
  await scenario();
  log(`PASS ${opts.scenario} in ${((Date.now() - t0) / 1000).toFixed(1)} s`);
} catch (e) {
  if (e instanceof Skip) {
    exitCode = SKIP;
    console.log(`SKIP: ${e.message}`);
  } else {
    exitCode = 1;
    console.log(`FAIL ${opts.scenario}: ${e instanceof Failure ? e.message : e.stack}`);
    await diagnose();
  }
} finally {
  for (const c of cleanups.reverse()) await c();
  if (!opts.keep) fs.rmSync(work, { recursive: true, force: true });
  else log(`kept ${work}`);
}
process.exit(exitCode);
