// The scenario trusted_root of run.mjs (CTest web.browser.trusted_root): the
// screen's own root certificate installed in Chromium's NSS database, and
// then no certificate error to ignore. Every other scenario launches Chromium
// with --ignore-certificate-errors, which also makes it treat the page as an
// installed app's would be; this one shows that a phone which installed the
// root gets the same without that switch (a secure context, the service
// worker, an installable app, "Share → umf"), and that a browser without the
// root refuses the screen.
//
// `t` holds what run.mjs shares with its scenarios (its helpers and state).
import { spawnSync } from 'node:child_process';
import crypto from 'node:crypto';
import fs from 'node:fs';
import https from 'node:https';
import path from 'node:path';

const sha256 = (bytes) => crypto.createHash('sha256').update(bytes).digest('hex');

export async function trustedRoot(t) {
  const { check, log, Failure } = t;
  if (spawnSync('certutil', ['-H'], { encoding: 'utf8' }).error?.code === 'ENOENT')
    throw new t.Skip('certutil is not installed (Debian\'s libnss3-tools, which scripts/install-deps.sh installs): ' +
                     'without it the root cannot be put in Chromium\'s NSS database');
  const video = t.fixture('tile0.y4m');
  const file = t.testFile('shared-on-trust.pdf', 96 * 1024 + 3);
  const dir = t.putDir();
  const provider = await t.startProvider({ extra: ['--puts', 'always', '--put-dir', dir] });
  const configDir = path.join(t.work, 'config');
  const fp = new URLSearchParams(new URL(provider.pairing).hash.slice(1)).get('fp');
  check(/^[0-9a-f]{64}$/.test(fp ?? ''), `the pairing URL carries a fingerprint (fp ${fp})`);

  // The root as the screen's person gets it.
  const rootPem = path.join(t.work, 'ROOT.pem');
  const exported = providerRun(t, ['trust', 'export', rootPem, '--config-dir', configDir]);
  check(exported.status === 0, `umf-provider trust export ROOT.pem exits 0 (${exported.status}: ${exported.stderr.trim()})`);
  const root = new crypto.X509Certificate(fs.readFileSync(rootPem));
  log(`root: ${root.subject.replace(/\n/g, ', ')}; valid ${root.validFrom} to ${root.validTo}`);
  check(sha256(root.raw) === fp, `the exported root is the pairing URL's fp (${sha256(root.raw)})`);
  check(root.ca && root.checkIssued(root) && root.verify(root.publicKey), 'it is a self-signed CA certificate');
  const told = providerRun(t, ['trust', '--config-dir', configDir]);
  check(told.status === 0 && told.stdout.includes(fp), `umf-provider trust prints it (${told.status})`);
  logNameConstraints(t, rootPem);

  // The root as the phone gets it, over a connection node checks against that
  // root alone: the chain the provider serves leads to it.
  const origin = new URL(provider.base).origin;
  const crt = await get(t, `${origin}/trust/umf-root.crt`, root.toString());
  log(`/trust/umf-root.crt: ${crt.status} ${crt.type}; ${crt.disposition}; the server's certificate names ` +
      `${crt.peerNames}`);
  check(crt.status === 200, `GET /trust/umf-root.crt without a token: 200, over TLS verified with the root (${crt.status})`);
  check(crt.type === 'application/x-x509-ca-cert', `served as application/x-x509-ca-cert (${crt.type})`);
  check(/^attachment\b/.test(crt.disposition ?? '') && /filename="umf-root\.crt"/.test(crt.disposition),
        `as the attachment umf-root.crt (${crt.disposition})`);
  check(sha256(crt.body) === fp, `its SHA-256 is the pairing URL's fp (${sha256(crt.body)})`);
  const profile = await get(t, `${origin}/trust/umf-root.mobileconfig`, root.toString());
  const plist = profile.body.toString('utf8');
  const data = /<data>([\s\S]*?)<\/data>/.exec(plist)?.[1].replace(/\s+/g, '') ?? '';
  check(profile.status === 200 && profile.type === 'application/x-apple-aspen-config',
        `GET /trust/umf-root.mobileconfig: ${profile.status}, ${profile.type}`);
  check(plist.includes('<string>com.apple.security.root</string>') && Buffer.from(data, 'base64').equals(root.raw),
        'the profile holds the root (a com.apple.security.root payload with its DER)');

  // A phone that installed the root: Chromium's NSS database in its HOME.
  const trustedHome = nssHome(t, 'home-trusted', rootPem);
  const untrustedHome = nssHome(t, 'home-untrusted', null);
  const chromiumVersion = spawnSync(t.opts.chromium, ['--version'], { encoding: 'utf8' }).stdout.trim();
  // Persistent: the contexts of chromium.launch are off the record, which
  // Chromium never offers to install ("in-incognito").
  const args = ['--autoplay-policy=no-user-gesture-required', '--use-fake-device-for-media-stream',
                '--use-fake-ui-for-media-stream', `--use-file-for-fake-video-capture=${video}`];
  if (process.getuid?.() === 0) args.push('--no-sandbox');  // Chromium's sandbox refuses root
  const started = Date.now();
  const context = await t.chromium.launchPersistentContext(path.join(t.work, 'chromium-trusted'), {
    executablePath: t.opts.chromium, headless: !t.opts.headed, args, env: { ...process.env, HOME: trustedHome },
    viewport: { width: 412, height: 915 }, hasTouch: true, timeout: 30000,
    handleSIGINT: false, handleSIGTERM: false, handleSIGHUP: false });
  t.cleanups.push(() => context.close().catch(() => {}));
  log(`${chromiumVersion} started in ${Date.now() - started} ms with HOME=${trustedHome}, ` +
      `no --ignore-certificate-errors (${args.join(' ')})`);
  let page;
  try {
    page = await t.openPage(null, t.pageUrl(provider.pairing, {}), { context });
  } catch (e) {
    throw new Failure(`Chromium with the root in its NSS database did not open the page: ${e.message.split('\n')[0]}`);
  }
  check(new URL(page.url()).origin === origin, `the navigation succeeded (${new URL(page.url()).origin})`);
  check(await page.evaluate(() => window.isSecureContext), 'window.isSecureContext');
  const sw = await page.waitForFunction(() => window.umfDebug?.serviceWorker, null, { timeout: 15000 })
    .then((h) => h.jsonValue(), () => null);
  check(sw === 'active', `the service worker registered (umfDebug.serviceWorker: ${sw})`);
  const cdp = await context.newCDPSession(page);
  let installability = null;
  for (const until = Date.now() + 10000; Date.now() < until;) {
    installability = (await cdp.send('Page.getInstallabilityErrors')).installabilityErrors;
    if (installability.length === 0) break;
    await t.sleep(250);
  }
  check(installability.length === 0,
        `Chromium finds the page installable (Page.getInstallabilityErrors: ${JSON.stringify(installability)})`);

  await t.waitForState(page, ['searching', 'locked'], 30000);
  await checkTrustSheet(t, page, fp, origin);

  const target = await t.readShareTarget(page, provider);
  await t.shareFile(page, target, file);
  await t.waitForState(page, ['locked'], 30000);
  await page.click('#grab');
  const r = await t.waitForPutResult(page, 30000);
  check(r.status === 'done' && r.outcome === 'saved', `the shared file put: done, saved (${r.status}, ${r.outcome})`);
  t.checkPutFolder(dir, file.name, file.bytes);

  // A phone that did not: the same URL is refused.
  const bare = await t.chromium.launch({ executablePath: t.opts.chromium, headless: !t.opts.headed, timeout: 30000,
                                         args: process.getuid?.() === 0 ? ['--no-sandbox'] : [],
                                         env: { ...process.env, HOME: untrustedHome },
                                         handleSIGINT: false, handleSIGTERM: false, handleSIGHUP: false });
  t.cleanups.push(() => bare.close().catch(() => {}));
  const refused = await (await bare.newContext()).newPage();
  const error = await refused.goto(t.pageUrl(provider.pairing, {}), { timeout: 20000 }).then(() => null, (e) => e.message);
  const code = /net::ERR_CERT_[A-Z_]+/.exec(error ?? '')?.[0];
  log(`without the root: ${error ? error.split('\n')[0].replace(/t=[^&]+/, 't=…') : 'the page loaded'}`);
  check(code !== undefined, `Chromium without the root in its NSS database refuses the screen (${code ?? error})`);
}

// The Trust sheet, reached from Pairing as a person would.
async function checkTrustSheet(t, page, fp, origin) {
  const { check, log } = t;
  await page.click('#show-pairing');
  await page.click('#show-trust');
  const shown = await page.waitForSelector('#trust-fingerprint[data-sha256]', { timeout: 10000 }).then(() => true, () => false);
  const sheet = await page.evaluate(() => {
    const $ = (id) => document.getElementById(id);
    return { visible: !$('trust').hidden, platform: $('trust').dataset.platform,
             sha256: $('trust-fingerprint').dataset.sha256, shown: $('trust-fingerprint').textContent.trim(),
             match: $('trust-match').dataset.match, matchText: $('trust-match').textContent.trim(),
             trusted: $('trust-state').dataset.trusted, state: $('trust-state').textContent.trim(),
             download: $('trust-download').href, other: $('trust-download-other').href };
  });
  log(`#trust: ${JSON.stringify(sheet)}`);
  check(shown && sheet.visible, 'Pairing → Trust this screen opens #trust with the fingerprint');
  check(sheet.sha256 === fp, `#trust-fingerprint is the root's, computed by the page (${sheet.sha256})`);
  check(sheet.shown.replace(/ /g, '').toLowerCase() === fp && /^([0-9A-F]{4} ){15}[0-9A-F]{4}$/.test(sheet.shown),
        `shown in groups of four (${sheet.shown})`);
  check(sheet.match === 'yes' && /matches the QR code/.test(sheet.matchText), `#trust-match says yes ("${sheet.matchText}")`);
  check(sheet.trusted === 'yes' && /trusts this screen/.test(sheet.state), `#trust-state says so ("${sheet.state}")`);
  check(sheet.download === `${origin}/trust/umf-root.crt` && sheet.other === `${origin}/trust/umf-root.mobileconfig`,
        `Linux gets the .crt, the profile offered besides (${sheet.download}, ${sheet.other})`);
  await page.click('#trust-close');
  check(await page.evaluate(() => document.getElementById('trust').hidden), 'Close hides the sheet');
}

function providerRun(t, args) {
  const r = spawnSync(t.opts.provider, args, { encoding: 'utf8', timeout: 20000,
                                               env: { ...process.env, XDG_RUNTIME_DIR: t.work } });
  return { status: r.error ? -1 : r.status, stdout: r.stdout ?? '', stderr: r.error ? r.error.message : r.stderr ?? '' };
}

// What the root may vouch for, for the log (the provider's tests check it).
function logNameConstraints(t, pem) {
  const r = spawnSync('openssl', ['x509', '-in', pem, '-noout', '-ext', 'nameConstraints'], { encoding: 'utf8' });
  if (r.status === 0) t.log(`root ${r.stdout.trim().replace(/\s*\n\s*/g, ' ')}`);
}

// A HOME whose NSS database (the one Chromium on Linux reads) trusts `rootPem` (one path or several) as a CA, or nothing.
export function nssHome(t, name, rootPem) {
  const home = path.join(t.work, name);
  const db = `sql:${path.join(home, '.pki', 'nssdb')}`;
  fs.mkdirSync(path.join(home, '.pki', 'nssdb'), { recursive: true });
  const run = (args) => {
    const r = spawnSync('certutil', args, { encoding: 'utf8' });
    if (r.status !== 0) throw new t.Failure(`certutil ${args.join(' ')} failed (${r.status}): ${r.stderr || r.stdout}`);
    return r.stdout;
  };
  run(['-N', '--empty-password', '-d', db]);
  // One root, or several (screens the phone pairs with).
  const roots = rootPem ? [rootPem].flat() : [];
  roots.forEach((pem, i) => {
    run(['-A', '-d', db, '-n', i ? `umf-screen-${i + 1}` : 'umf-screen', '-t', 'C,,', '-i', pem]);
    t.log(`NSS database ${db}: ${run(['-L', '-d', db]).trim().split('\n').pop().replace(/\s+/g, ' ')}`);
  });
  return home;
}

// GET over TLS that trusts `ca` alone: {status, type, disposition, body, peerNames}.
function get(t, url, ca) {
  return new Promise((resolve, reject) => {
    const req = https.get(url, { ca, rejectUnauthorized: true, agent: false }, (res) => {
      const peerNames = res.socket.getPeerCertificate()?.subjectaltname;
      const chunks = [];
      res.on('data', (c) => chunks.push(c));
      res.on('end', () => resolve({ status: res.statusCode, type: res.headers['content-type'],
                                    disposition: res.headers['content-disposition'], body: Buffer.concat(chunks),
                                    peerNames }));
    });
    req.on('error', (e) => reject(new t.Failure(`GET ${url}, trusting the root alone, failed: ${e.message}`)));
  });
}
