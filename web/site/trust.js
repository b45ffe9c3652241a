// "Trust this screen": the screen is its own small certificate authority,
// and a phone that installs its root stops warning about the screen's
// certificate, and can install the page as an app that takes shares (a
// service worker needs a trusted certificate). Never required: a phone that
// accepted the warning works the same. The fingerprint is computed here from
// the very bytes the phone downloads, so that what the person compares is
// what gets installed, not what the screen claims.
import { $ } from './sheets.js';
import { Sha256 } from './sha256.js';

const ROOT_CRT = 'trust/umf-root.crt';
const ROOT_PROFILE = 'trust/umf-root.mobileconfig';

// iPadOS asks for desktop pages and says "Macintosh": only its touch points tell.
export function phoneKind(nav = navigator) {
  const ua = nav.userAgent || '';
  if (/iPhone|iPad|iPod/.test(ua) || (/Macintosh/.test(ua) && nav.maxTouchPoints > 1)) return 'ios';
  if (/Android/.test(ua)) return 'android';
  return 'other';
}

const STEPS = {
  android: [
    'Tap Get the certificate: umf-root.crt is saved to Downloads.',
    'Open Settings → Security (or Security & privacy) → More security settings → Encryption & credentials → ' +
      'Install a certificate → CA certificate.',
    'Tap Install anyway, then pick umf-root.crt.',
    'Reload this page.',
  ],
  ios: [
    'Tap Get the profile, then Allow.',
    'Open Settings → Profile Downloaded → Install.',
    'Then Settings → General → About → Certificate Trust Settings: switch on “umf screen root”.',
    'Reload this page.',
  ],
  other: [
    'Tap Get the certificate: umf-root.crt.',
    'Add it to the trusted certificate authorities of the system or the browser.',
    'Reload this page.',
  ],
};

// As `umf-provider trust` prints it for people: "AB12 CD34 …".
export const forPeople = (hex) => (hex || '').toUpperCase().replace(/(.{4})(?=.)/g, '$1 ');

let rootHex = null;  // a promise of the root's fingerprint, fetched once per page

function fetchRootFingerprint() {
  rootHex ??= fetch(ROOT_CRT, { cache: 'no-store' }).then(async (r) => {
    if (!r.ok) throw new Error(`the screen answered ${r.status}`);
    return new Sha256().update(new Uint8Array(await r.arrayBuffer())).hex();
  });
  // A failure (an older provider, a broken connection) is not kept: opening the sheet again retries.
  rootHex.catch(() => { rootHex = null; });
  return rootHex;
}

// `form`: 'crt' (DER, Android and most systems) or 'profile' (iOS).
function offer(a, form, label) {
  a.href = form === 'profile' ? ROOT_PROFILE : ROOT_CRT;
  a.textContent = label;
  // iOS offers to install a profile only when Safari opens it, not when it saves it to Files.
  if (form === 'profile') a.removeAttribute('download');
  else a.download = 'umf-root.crt';
}

// Text with `code` in backquotes, as the page shows commands.
function withCode(el, text) {
  el.replaceChildren(...text.split('`').map((part, i) => (i % 2 ? Object.assign(document.createElement('code'),
                                                                                  { textContent: part }) : part)));
}

// The service worker is there for "Share → umf" (sw.js), and browsers
// register one only where the certificate is trusted: so its registration
// (`debug.serviceWorker`, umfDebug's) also tells the Trust sheet, which may
// be open while it ends, and whether the page may move to the screen's
// name (screen_name.js). Resolves to the status it ends with.
export function registerServiceWorker(debug) {
  const is = (status) => {
    debug.serviceWorker = status;
    showTrustState(status);
    return status;
  };
  if (!navigator.serviceWorker) return Promise.resolve(is('unsupported'));
  // A module worker, so that it shares carry.js with the page. Without it
  // (an untrusted certificate, an older browser) the page works the same,
  // only "Share → umf" does not.
  return navigator.serviceWorker.register('sw.js', { type: 'module' }).then(
    () => navigator.serviceWorker.ready.then(() => is('active')),
    (e) => is(`not registered: ${e.message}`));
}

// `status`: registerServiceWorker's, null while not known yet.
function showTrustState(status) {
  const el = $('trust-state');
  let trusted = 'unknown';
  let text = 'Checking whether this phone trusts this screen…';
  if (status === 'active') {
    trusted = 'yes';
    text = 'This phone trusts this screen.';
  } else if (status === 'unsupported') {
    text = 'This browser does not tell whether it trusts this screen.';
  } else if (status) {
    trusted = 'no';
    text = 'This phone does not trust this screen yet: its browser warned about the certificate.';
  }
  el.dataset.trusted = trusted;
  el.textContent = text;
}

// `pairedFingerprint()`: what the pairing URL carried (fp), null when this
// phone is not paired with this screen.
export function wireTrust(pairedFingerprint, debug) {
  $('show-trust').addEventListener('click', () => {
    $('pairing').hidden = true;
    showTrust(pairedFingerprint(), debug.serviceWorker);
  });
  $('trust-close').addEventListener('click', () => ($('trust').hidden = true));
}

async function showTrust(paired, serviceWorker) {
  const kind = phoneKind();
  $('trust').dataset.platform = kind;
  if (kind === 'ios') {
    offer($('trust-download'), 'profile', 'Get the profile');
    offer($('trust-download-other'), 'crt', 'umf-root.crt (Android and others)');
  } else {
    offer($('trust-download'), 'crt', 'Get the certificate');
    offer($('trust-download-other'), 'profile', 'umf-root.mobileconfig (iPhone, iPad)');
  }
  $('trust-steps').replaceChildren(...STEPS[kind].map((s) => {
    const li = document.createElement('li');
    li.textContent = s;
    return li;
  }));
  showTrustState(serviceWorker);
  $('trust').hidden = false;

  const fp = $('trust-fingerprint');
  const match = $('trust-match');
  fp.textContent = '…';
  delete fp.dataset.sha256;
  delete match.dataset.match;
  match.textContent = '';
  let hex;
  try {
    hex = await fetchRootFingerprint();
  } catch (e) {
    $('trust').dataset.available = 'no';
    fp.textContent = '—';
    match.dataset.match = 'no';
    match.textContent = `The screen did not give its certificate (${e.message}): it may run an older umf-provider.`;
    return;
  }
  $('trust').dataset.available = 'yes';
  fp.dataset.sha256 = hex;
  fp.textContent = forPeople(hex);
  const same = !!paired && paired.toLowerCase() === hex;
  match.dataset.match = same ? 'yes' : 'no';
  withCode(match, same
    ? '✓ This matches the QR code you scanned.'
    : paired
      ? 'This is not the fingerprint of the QR code you scanned: compare it with what `umf-provider trust` ' +
        'prints on the screen before you install it.'
      : 'Compare it with what `umf-provider trust` prints on the screen before you install it.');
}
