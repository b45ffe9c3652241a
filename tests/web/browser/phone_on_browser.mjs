// The phone pointed at a browser window, as pictures for the README
// (scripts/screenshots-browser.sh runs it against a provider on a desktop):
// the phone page in a phone-sized headless Chromium whose fake camera plays
// VIDEO, paired by PAIRING. Waits until the lock's title names a link, then
// grabs it.
//
//   node tests/web/browser/phone_on_browser.mjs --pairing URL --video CAMERA.y4m \
//        --modules build/X/tests/web/browser/node_modules --out docs/images [--chromium PATH]
//        [--expect-title TITLE] [--expect-url URL]
//
// Writes phone-browser-link.jpg (locked: "Link: ...") and
// phone-browser-result.jpg (the link taken). Exit 1 with the page's states
// when the title never names a link, the grab brings no URL, or either is
// not the one expected.
import fs from 'node:fs';
import { createRequire } from 'node:module';
import path from 'node:path';

const args = {};
for (let i = 2; i + 1 < process.argv.length; i += 2) args[process.argv[i].replace(/^--/, '')] = process.argv[i + 1];
for (const k of ['pairing', 'video', 'modules', 'out'])
  if (!args[k]) {
    console.error(`phone_on_browser.mjs: --${k} is needed`);
    process.exit(2);
  }
const { chromium } = createRequire(path.join(path.resolve(args.modules), 'noop.js'))('playwright-core');
fs.mkdirSync(args.out, { recursive: true });

const browser = await chromium.launch({
  executablePath: args.chromium ?? '/usr/bin/chromium', headless: true,
  args: ['--ignore-certificate-errors', '--use-fake-device-for-media-stream', '--use-fake-ui-for-media-stream',
         `--use-file-for-fake-video-capture=${path.resolve(args.video)}`, '--no-sandbox'],
});
const titles = [];
let page;
try {
  const phone = { viewport: { width: 390, height: 844 }, deviceScaleFactor: 1.5, isMobile: true, hasTouch: true,
                  ignoreHTTPSErrors: true };
  page = await (await browser.newContext(phone)).newPage();
  await page.goto(args.pairing);
  // Titles seen on the way: the first aim at a tab may name the page.
  await page.exposeFunction('umfSawTitle', (t) => titles.push(t));
  await page.evaluate(() => {
    const title = document.getElementById('target-title');
    new MutationObserver(() => window.umfSawTitle(title.textContent)).observe(title, { childList: true, subtree: true,
                                                                                       characterData: true });
  });
  // The picture is taken when the lock has named the link for 300 ms (the
  // ring settled on the last aim); a title that changed in between is
  // waited for again, a few times at most.
  let title = '';
  for (let attempt = 0; attempt < 3 && !title.startsWith('Link: '); ++attempt) {
    await page.waitForFunction(() => document.body.dataset.state === 'locked' &&
                                      document.getElementById('target-title').textContent.startsWith('Link: '),
                               null, { timeout: 45000 });
    await page.waitForTimeout(300);
    await page.screenshot({ path: path.join(args.out, 'phone-browser-link.jpg'), type: 'jpeg', quality: 80 });
    title = await page.textContent('#target-title');
  }
  await page.click('#grab');
  await page.waitForSelector('#result[data-kind="url"]', { timeout: 20000 });
  const url = await page.getAttribute('#result', 'data-url');
  await page.screenshot({ path: path.join(args.out, 'phone-browser-result.jpg'), type: 'jpeg', quality: 80 });
  console.log(`locked: ${title}\ngrabbed: ${url}`);
  if (args['expect-title'] !== undefined && title !== args['expect-title'])
    throw new Error(`the locked title is "${title}", not "${args['expect-title']}"`);
  if (args['expect-url'] !== undefined && url !== args['expect-url'])
    throw new Error(`the grab brought ${url}, not ${args['expect-url']}`);
} catch (e) {
  const state = page ? await page.evaluate(() => document.body.dataset.state).catch(() => '?') : '?';
  console.error(`phone_on_browser.mjs: ${e.message}\nstate: ${state}\ntitles seen: ${JSON.stringify(titles)}`);
  process.exitCode = 1;
} finally {
  await browser.close();
}
