// The phone flow as pictures for the README: the page in a phone-sized
// headless Chromium, its fake camera a simulated photo video of a board tile
// (the web.browser.video_file fixture), against a headless provider.
//
//   node tests/web/browser/screenshots.mjs --provider build/X/bin/umf-provider --site build/X/web/site \
//        --board tests/web/browser/board/board.json --video build/X/tests/web/browser/tile0.y4m \
//        --modules build/X/tests/web/browser/node_modules --out docs/images
//
// Writes phone-locked.jpg (the lock ring and the title of what a grab would
// take), phone-result.jpg (the file taken and checked), phone-put-asking.jpg
// (a file put on the screen, waiting for the person there to accept it),
// phone-put-done.jpg (accepted and saved), phone-unpaired.jpg, and the
// Trust this screen sheet as an Android phone and an iPhone see it before
// they trust the screen (trust-android.png, trust-ios.png).
import { spawn, spawnSync } from 'node:child_process';
import fs from 'node:fs';
import { createRequire } from 'node:module';
import os from 'node:os';
import path from 'node:path';

const args = {};
for (let i = 2; i + 1 < process.argv.length; i += 2) args[process.argv[i].replace(/^--/, '')] = process.argv[i + 1];
for (const k of ['provider', 'site', 'board', 'video', 'modules', 'out'])
  if (!args[k]) {
    console.error(`screenshots.mjs: --${k} is needed`);
    process.exit(2);
  }
const { chromium } = createRequire(path.join(path.resolve(args.modules), 'noop.js'))('playwright-core');
const work = fs.mkdtempSync(path.join(os.tmpdir(), 'umf-phone-shots-'));
fs.mkdirSync(args.out, { recursive: true });

// The screen's own field: the one the video of the board shows.
fs.mkdirSync(path.join(work, 'config'), { recursive: true });
fs.copyFileSync(path.join(path.dirname(path.resolve(args.board)), 'field-seed'), path.join(work, 'config', 'field-seed'));
const provider = spawn(args.provider, ['serve', '--headless', '--board', path.resolve(args.board), '--screen', '1920x1080',
                                       '--port', '0', '--bind', '127.0.0.1', '--config-dir', path.join(work, 'config'),
                                       '--no-qr', '--web', args.site, '--puts', 'ask', '--put-dir', path.join(work, 'puts')],
                       { stdio: ['ignore', 'pipe', 'inherit'], env: { ...process.env, XDG_RUNTIME_DIR: work } });
const pairing = await new Promise((resolve, reject) => {
  let out = '';
  const timer = setTimeout(() => reject(new Error(`no pairing URL from the provider:\n${out}`)), 20000);
  provider.stdout.on('data', (d) => {
    out += d;
    const m = /^pairing URL: (\S+)$/m.exec(out);
    if (m) {
      clearTimeout(timer);
      resolve(m[1]);
    }
  });
});
// `umf-provider puts ...` at this provider: the person at the screen answering.
const puts = (...more) => {
  const r = spawnSync(args.provider, ['puts', ...more, '--port', new URL(pairing).port],
                      { encoding: 'utf8', env: { ...process.env, XDG_RUNTIME_DIR: work } });
  if (r.status !== 0) throw new Error(`umf-provider puts ${more.join(' ')}: ${r.stderr}`);
  return r.stdout;
};

const browser = await chromium.launch({
  executablePath: args.chromium ?? '/usr/bin/chromium', headless: true,
  args: ['--ignore-certificate-errors', '--use-fake-device-for-media-stream', '--use-fake-ui-for-media-stream',
         `--use-file-for-fake-video-capture=${path.resolve(args.video)}`, '--no-sandbox'],
});
try {
  const phone = { viewport: { width: 390, height: 844 }, deviceScaleFactor: 1.5, isMobile: true, hasTouch: true,
                  ignoreHTTPSErrors: true };
  const page = await (await browser.newContext(phone)).newPage();
  await page.goto(pairing);
  await page.waitForSelector('body[data-state="locked"]', { timeout: 30000 });
  await page.waitForFunction(() => document.getElementById('target-title').textContent.length > 0, null, { timeout: 10000 });
  await page.screenshot({ path: path.join(args.out, 'phone-locked.jpg'), type: 'jpeg', quality: 80 });
  await page.click('#grab');
  await page.waitForSelector('#result[data-verified="true"]', { timeout: 20000 });
  await page.screenshot({ path: path.join(args.out, 'phone-result.jpg'), type: 'jpeg', quality: 80 });

  // Put: a file from the phone to where it points, asked at the screen.
  const slides = path.join(work, 'Project review slides.pdf');
  fs.writeFileSync(slides, Buffer.alloc(2_400_000, 0x25));
  await page.click('#result-close');
  await page.click('#show-put');
  await page.setInputFiles('#put-file', slides);
  await page.waitForSelector('body[data-state="locked"]', { timeout: 30000 });
  await page.click('#grab');
  await page.waitForSelector('#put-status[data-status="asking"]', { timeout: 20000 });
  let waiting = [];
  for (let i = 0; i < 100 && !waiting.length; ++i) {
    const listed = JSON.parse(puts('--json'));
    waiting = Array.isArray(listed) ? listed : Object.values(listed).find(Array.isArray) ?? [];
    if (!waiting.length) await page.waitForTimeout(100);
  }
  await page.waitForTimeout(1200);  // the countdown has begun
  await page.screenshot({ path: path.join(args.out, 'phone-put-asking.jpg'), type: 'jpeg', quality: 80 });
  puts('--accept', String(waiting[0].id));
  await page.waitForSelector('#put-status[data-status="done"]', { timeout: 20000 });
  await page.screenshot({ path: path.join(args.out, 'phone-put-done.jpg'), type: 'jpeg', quality: 80 });

  const fresh = await (await browser.newContext(phone)).newPage();
  await fresh.goto(new URL(pairing).origin + '/');
  await fresh.waitForSelector('body[data-state="unpaired"]', { timeout: 10000 });
  await fresh.screenshot({ path: path.join(args.out, 'phone-unpaired.jpg'), type: 'jpeg', quality: 80 });

  // This Chromium ignores certificate errors, so it would register the
  // service worker as on a trusted screen; the pictures show a phone that only
  // accepted the warning, whose registration fails as Chromium's then does.
  const phones = {
    android: { ...phone, viewport: { width: 412, height: 915 },
               userAgent: 'Mozilla/5.0 (Linux; Android 14; Pixel 7) AppleWebKit/537.36 (KHTML, like Gecko) ' +
                          'Chrome/126.0.0.0 Mobile Safari/537.36' },
    ios: { ...phone, userAgent: 'Mozilla/5.0 (iPhone; CPU iPhone OS 17_5 like Mac OS X) AppleWebKit/605.1.15 ' +
                                '(KHTML, like Gecko) Version/17.5 Mobile/15E148 Safari/604.1' },
  };
  for (const [name, device] of Object.entries(phones)) {
    const context = await browser.newContext(device);
    await context.addInitScript(() => {
      navigator.serviceWorker.register = () => Promise.reject(new DOMException(
        'Failed to register a ServiceWorker: An SSL certificate error occurred when fetching the script.', 'SecurityError'));
    });
    const trust = await context.newPage();
    await trust.goto(pairing);
    await trust.waitForSelector('body[data-state="locked"], body[data-state="searching"]', { timeout: 30000 });
    await trust.click('#show-pairing');
    await trust.click('#show-trust');
    await trust.waitForSelector('#trust-fingerprint[data-sha256]', { timeout: 10000 });
    await trust.waitForSelector('#trust-state[data-trusted="no"]', { timeout: 10000 });
    await trust.screenshot({ path: path.join(args.out, `trust-${name}.png`) });
  }
  console.log('wrote phone-locked.jpg, phone-result.jpg, phone-put-asking.jpg, phone-put-done.jpg, phone-unpaired.jpg, ' +
              `trust-android.png, trust-ios.png to ${args.out}`);
} finally {
  await browser.close();
  provider.kill('SIGTERM');
}
