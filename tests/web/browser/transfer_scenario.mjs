// The scenarios cut_download and cut_put of run.mjs (CTest
// web.browser.cut_download, web.browser.cut_put): a 200 MB file carried
// between the page and a real provider through a relay that cuts the
// connection once, when half the file has passed (tests/support/
// cutting_relay.py). The page must go on from where it was cut, say so, and
// end with the whole file checked, having carried at most 1.25 times its
// size.
//
// `t` holds what run.mjs shares with its scenarios (its helpers and state).
import { spawn } from 'node:child_process';
import crypto from 'node:crypto';
import fs from 'node:fs';
import path from 'node:path';

const SIZE = 200 * 1000 * 1000;
const relayScript = path.join(path.dirname(new URL(import.meta.url).pathname), '..', '..', 'support', 'cutting_relay.py');

// The relay to `provider`, cutting `direction` (down: to the page; up: from
// it) at half the file: {port, carried()} with carried() the bytes each way.
async function startRelay(t, provider, direction) {
  const counts = path.join(t.work, 'relay-counts');
  const relay = spawn('python3', [relayScript, String(provider.port), String(SIZE / 2), counts, direction],
                      { stdio: ['ignore', 'pipe', 'inherit'] });
  t.cleanups.push(async () => { relay.kill('SIGTERM'); });
  const port = await new Promise((resolve) => {
    let out = '';
    relay.stdout.on('data', (d) => {
      out += d;
      if (out.includes('\n')) resolve(Number(out.trim()));
    });
    relay.on('exit', () => resolve(null));
  });
  if (!port) throw new t.Failure('the relay did not start');
  const carried = () => {
    const [down, up] = fs.readFileSync(counts, 'utf8').trim().split(' ').map(Number);
    return { down, up };
  };
  return { port, carried };
}

// The page at the relay's port instead of the provider's, and every text
// #selector showed, in order.
async function openThroughRelay(t, provider, relay, query, selector) {
  const pairing = new URL(provider.pairing);
  pairing.port = String(relay.port);
  const browser = await t.launch({ video: t.fixture('tile0.y4m') });
  const page = await t.openPage(browser, t.pageUrl(pairing.toString(), query));
  const texts = [];
  await page.exposeFunction('__umfText', (text) => texts.push(text));
  await page.evaluate((sel) => {
    const watch = () => {
      const e = document.querySelector(sel);
      if (!e) return setTimeout(watch, 50);
      new MutationObserver(() => window.__umfText(e.textContent))
        .observe(e, { childList: true, characterData: true, subtree: true });
    };
    watch();
  }, selector);
  return { page, texts };
}

// The file of tile 0 made SIZE random bytes, in a copy of the board.
function bigBoard(t) {
  const boardDir = path.join(t.work, 'board');
  fs.mkdirSync(boardDir);
  const original = path.dirname(path.resolve(t.opts.board));
  for (const f of fs.readdirSync(original)) fs.copyFileSync(path.join(original, f), path.join(boardDir, f));
  const expected = t.item(0);
  expected.path = path.join(boardDir, expected.file);
  fs.writeFileSync(expected.path, crypto.randomBytes(SIZE));
  expected.size = SIZE;
  expected.sha256 = crypto.createHash('sha256').update(fs.readFileSync(expected.path)).digest('hex');
  return { board: path.join(boardDir, path.basename(t.opts.board)), expected };
}

export async function cutDownload(t) {
  const { check, log } = t;
  const { board, expected } = bigBoard(t);
  const provider = await t.startProvider({ board });
  const relay = await startRelay(t, provider, 'down');
  const { page, texts } = await openThroughRelay(t, provider, relay, { autograb: '1' }, '#status');
  await t.waitForState(page, ['result'], 120000);
  const resumes = await page.evaluate(() => window.umfDebug.downloadResumes ?? []);
  log(`resumes: ${JSON.stringify(resumes)}`);
  check(resumes.length >= 1, 'the download was cut and the page resumed it');
  check(texts.some((x) => /^Connection lost at [\d.]+ MB of 190\.7 MB, resuming…$/.test(x)),
        `the page said where the connection was lost (${texts.filter((x) => x.startsWith('Conn')).join(' | ')})`);
  await t.checkFileResult(page, expected);
  await t.sleep(300);
  const { down } = relay.carried();
  log(`the relay carried ${down} bytes to the page for a file of ${SIZE}`);
  check(down <= SIZE * 1.25, `at most 1.25 times the file was carried (${(down / SIZE).toFixed(3)})`);
}

export async function cutPut(t) {
  const { check, log } = t;
  const file = t.testFile('recording.bin', SIZE);
  const dir = t.putDir();
  const provider = await t.startProvider({ extra: ['--puts', 'always', '--put-dir', dir, '--put-max-mb', '1000'] });
  const relay = await startRelay(t, provider, 'up');
  const { page, texts } = await openThroughRelay(t, provider, relay, { autoput: '1' }, '#put-status-text');
  await t.openPutChooser(page);
  await page.setInputFiles('#put-file', file.path);
  log(`set ${file.name} (${file.size} bytes) on #put-file`);
  const r = await t.waitForPutResult(page, 120000);
  check(r.status === 'done' && r.outcome === 'saved', `#put-status done, saved (${r.status}, ${r.outcome})`);
  const resumes = await page.evaluate(() => window.umfDebug.putResumes ?? []);
  log(`resumed at: ${JSON.stringify(resumes)}`);
  check(resumes.length >= 1, 'the upload was cut and the page went on from what the screen held');
  check(texts.some((x) => /^Connection lost at [\d.]+ MB of 190\.7 MB, resuming…$/.test(x)),
        `the page said where the connection was lost (${texts.filter((x) => x.startsWith('Conn')).join(' | ')})`);
  t.checkPutFolder(dir, file.name, file.bytes);
  const { up } = relay.carried();
  log(`the relay carried ${up} bytes from the page for a file of ${SIZE}`);
  check(up <= SIZE * 1.25, `at most 1.25 times the file was carried (${(up / SIZE).toFixed(3)})`);
}
