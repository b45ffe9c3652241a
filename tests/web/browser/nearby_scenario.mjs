// The scenario nearby_screen of run.mjs, run by the CTest test
// discovery.nearby_screen (tests/discovery/page_by_name_test.sh) inside a
// "phone" network namespace of its own, joined by a veth pair to the
// screens' one, where two screens run side by side: a and b, each with a
// field of its own, both announced over DNS-SD. A phone that trusts both
// roots pairs with b, then with a; pointed at b while on a's page, the page
// says it is another screen and offers b's page, found by b's field; the
// offer opens b's page, paired already, which grabs from b. A phone that
// trusts a's root alone is offered nothing: its browser cannot fetch b's
// field, and could not open b's page either.
//
// Options of its own: --pairing URL and --root PEM (a's), --other-pairing
// URL and --other-root PEM (b's). `t` holds what run.mjs shares with its
// scenarios.
import path from 'node:path';
import { grabTile0, launchPhone } from './name_scenario.mjs';
import { nssHome } from './trust_scenario.mjs';

export async function nearbyScreen(t) {
  const { opts, check, log, Failure } = t;
  for (const k of ['pairing', 'root', 'other-pairing', 'other-root'])
    if (!opts[k]) throw new Failure(`nearby_screen needs --${k} (tests/discovery/page_by_name_test.sh gives it)`);
  const byName = (pairing) => {
    const u = new URL(pairing);
    return `https://${new URLSearchParams(u.hash.slice(1)).get('n')}:${u.port}`;
  };
  const a = byName(opts.pairing), b = byName(opts['other-pairing']);
  const expected = t.item(0);
  const video = t.fixture('other_screen_tile0.y4m');  // b's field, the board's first tile
  const home = nssHome(t, 'phone-home', [opts.root, opts['other-root']]);
  const context = await launchPhone(t, path.join(t.work, 'phone-profile'), home, video);

  // Pairing with b: its QR code, then the page moves to b's name and locks on b.
  let page = await t.openPage(null, t.pageUrl(opts['other-pairing'], {}), { context });
  await page.waitForURL((u) => u.origin === b, { timeout: 15000 }).catch(() => {});
  check(new URL(page.url()).origin === b, `b's page moved to its name ${b} (${new URL(page.url()).origin})`);
  await t.waitForState(page, ['locked'], 45000);
  log('b\'s page locks on b');
  await page.close();

  // Pairing with a, the camera still on b: another screen, and b is offered.
  page = await t.openPage(null, t.pageUrl(opts.pairing, {}), { context });
  await page.waitForURL((u) => u.origin === a, { timeout: 15000 }).catch(() => {});
  check(new URL(page.url()).origin === a, `a's page moved to its name ${a} (${new URL(page.url()).origin})`);
  const offer = await page.waitForFunction(() => {
    const link = document.querySelector('#hint:not([hidden]) #hint-link');
    return link ? { href: link.getAttribute('href'), text: document.querySelector('#hint').textContent,
                    code: document.querySelector('#hint').dataset.code } : null;
  }, null, { timeout: 45000 }).then((h) => h.jsonValue()).catch(() => null);
  const d = await t.debugOf(page);
  log(`#hint: ${JSON.stringify(offer)}; nearby ${JSON.stringify(d?.nearby)}`);
  check(offer && offer.code === 'another-screen', `a's page says it sees another screen (${offer?.code})`);
  check(offer.href === `${b}/`, `and offers b's page ${b}/ (${offer.href})`);
  check(/another screen, umf on umf-screen-test/.test(offer.text) && /open its page/.test(offer.text),
        `naming b ("${offer.text}")`);
  const states = await page.evaluate(() => window.__umfStates.map(([, s]) => s));
  check(!states.includes('locked') && !states.includes('result'), `a's page never locked (${[...new Set(states)].join(', ')})`);

  // The offer taken: b's page, with the pairing this phone has there, grabs from b.
  await page.click('#hint-link');
  await page.waitForURL((u) => u.origin === b, { timeout: 15000 }).catch(() => {});
  check(new URL(page.url()).origin === b, `the offer opened b's page (${new URL(page.url()).origin})`);
  await grabTile0(t, page, expected);
  await context.close();
  await nothingOffered(t, a, video);
}

// The same phone with a's root alone: b is listed, its field cannot be
// fetched, the hint stays plain. `a` is a's page at its name.
export async function nothingOffered(t, a, video) {
  const home = nssHome(t, 'other-phone-home', [t.opts.root]);
  const context = await launchPhone(t, path.join(t.work, 'other-phone-profile'), home, video);
  const page = await t.openPage(null, t.pageUrl(t.opts.pairing, {}), { context });
  await page.waitForURL((u) => u.origin === a, { timeout: 15000 }).catch(() => {});
  await page.waitForFunction(() => window.umfDebug?.nearby?.listed > 0 &&
                                    document.querySelector('#hint')?.dataset.code === 'another-screen',
                              null, { timeout: 45000 }).catch(() => {});
  await t.sleep(4000);  // the fetch of b's field refused, and a few more frames of b
  const { tried, hint } = await page.evaluate(() => ({
    tried: window.umfDebug?.nearby,
    hint: { link: !!document.querySelector('#hint-link'), text: document.querySelector('#hint').textContent } }));
  t.log(`nearby ${JSON.stringify(tried)}; #hint ${JSON.stringify(hint)}`);
  t.check(tried && tried.listed === 1 && tried.fetched === 0, `b is listed, and its field not fetched (${JSON.stringify(tried)})`);
  t.check(!hint.link && /scan its QR code/.test(hint.text), `the plain hint, no offer ("${hint.text}")`);
  await context.close();
}
