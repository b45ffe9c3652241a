// The scenario name_follows of run.mjs, run by the CTest test
// discovery.page_by_name (tests/discovery/page_by_name_test.sh) inside a
// "phone" network namespace of its own, with its own avahi-daemon, joined to
// the screen's by a veth pair: a phone that trusts the screen's root opens
// the QR code's address, the page moves to the screen's .local name (found
// by multicast DNS across the link) and grabs there; the screen's address
// then changes, and the page, opened again as an installed app opens it
// (the name, no fragment), finds the screen at its new address with the
// pairing it kept.
//
// Options of its own: --pairing URL (the provider's, which the test started
// in the screen's namespace), --root PEM (the screen's root), --move CMD
// (a shell command that moves the screen to --new-address ADDRESS).
// `t` holds what run.mjs shares with its scenarios.
import { execFileSync, spawnSync } from 'node:child_process';
import path from 'node:path';
import { nssHome } from './trust_scenario.mjs';

export async function nameFollows(t) {
  const { opts, check, log, Failure } = t;
  for (const k of ['pairing', 'root', 'move', 'new-address'])
    if (!opts[k]) throw new Failure(`name_follows needs --${k} (tests/discovery/page_by_name_test.sh gives it)`);
  const pairing = new URL(opts.pairing);
  const name = new URLSearchParams(pairing.hash.slice(1)).get('n');
  check(/\.local$/.test(name ?? ''), `the pairing URL names the screen (n=${name}) besides its address ${pairing.hostname}`);
  const byName = `https://${name}:${pairing.port}`;
  const expected = t.item(0);
  const video = t.fixture('tile0.y4m');
  const home = nssHome(t, 'phone-home', opts.root);
  const profile = path.join(t.work, 'phone-profile');

  // First contact: the QR code's address.
  let context = await launchPhone(t, profile, home, video);
  let page = await t.openPage(null, t.pageUrl(opts.pairing, {}), { context });
  await page.waitForURL((u) => u.hostname === name, { timeout: 15000 }).catch(() => {});
  check(new URL(page.url()).origin === byName, `the page moved from ${pairing.origin} to ${byName} (${new URL(page.url()).origin})`);
  await grabTile0(t, page, expected);
  check(!new URL(page.url()).hash.includes('t='), 'the token left the address bar at the name as well');

  // The screen's address changes.
  await context.close();
  const before = resolved(name);
  execFileSync('sh', ['-c', opts.move], { stdio: 'inherit' });
  let after = resolved(name);
  for (const until = Date.now() + 15000; after !== opts['new-address'] && Date.now() < until; after = resolved(name))
    await t.sleep(250);
  log(`${name}: ${before} before the move, ${after} after`);
  check(after === opts['new-address'], `the phone's resolver finds ${name} at the new address ${opts['new-address']} (${after})`);
  const old = await fetchStatus(t, pairing.origin);
  check(old === 'unreachable', `the QR code's address ${pairing.origin} no longer answers (${old})`);

  // The app opened again, the next day: the name, no pairing in the URL.
  context = await launchPhone(t, profile, home, video);
  page = await t.openPage(null, `${byName}/`, { context });
  check(new URL(page.url()).origin === byName, `the page opened at ${byName}`);
  await grabTile0(t, page, expected);
  const d = await t.debugOf(page);
  check(d.transport === 'ws', `over the secure WebSocket, with the pairing kept at the name (${d.transport})`);
}

// Chromium as the phone: the root in its NSS database, no certificate error
// ignored, a profile kept between launches (localStorage, the service worker).
export async function launchPhone(t, profile, home, video) {
  const args = ['--autoplay-policy=no-user-gesture-required', '--use-fake-device-for-media-stream',
                '--use-fake-ui-for-media-stream', `--use-file-for-fake-video-capture=${video}`];
  if (process.getuid?.() === 0) args.push('--no-sandbox');  // Chromium's sandbox refuses root
  const context = await t.chromium.launchPersistentContext(profile, {
    executablePath: t.opts.chromium, headless: !t.opts.headed, args, env: { ...process.env, HOME: home },
    viewport: { width: 412, height: 915 }, hasTouch: true, timeout: 30000,
    handleSIGINT: false, handleSIGTERM: false, handleSIGHUP: false });
  t.cleanups.push(() => context.close().catch(() => {}));
  return context;
}

export async function grabTile0(t, page, expected) {
  await t.waitForState(page, ['locked'], 45000);
  await page.click('#grab');
  await t.waitForState(page, ['result'], 30000);
  await t.checkFileResult(page, expected);
}

// The name's IPv4 address as this namespace's resolver gives it (nss-mdns
// asking the phone's avahi-daemon), or null.
function resolved(name) {
  const r = spawnSync('getent', ['ahostsv4', name], { encoding: 'utf8', timeout: 5000 });
  return r.status === 0 ? [...new Set(r.stdout.split('\n').map((l) => l.split(/\s+/)[0]).filter(Boolean))].join(' ') || null
                        : null;
}

// 'answers' or 'unreachable', within 3 s, whatever the certificate.
async function fetchStatus(t, origin) {
  const r = spawnSync('curl', ['-sk', '-o', '/dev/null', '--max-time', '3', `${origin}/`], { timeout: 5000 });
  return r.status === 0 ? 'answers' : 'unreachable';
}
