// Pairing: the token, the root certificate's fingerprint and the screen's
// .local name arrive in the URL's fragment from the provider's QR code
// (https://host:port/#t=TOKEN&fp=HEX&n=NAME.local), which browsers never
// send to a server. They are kept on the phone per
// screen (origin), and the fragment is then taken out of the address bar so
// the token does not linger in a shared screenshot or the history.
import { parsePairingUrl } from './pointer.js';

const KEY = 'umf.pairings.v1';

function loadAll() {
  try {
    const all = JSON.parse(localStorage.getItem(KEY) || '{}');
    return all && typeof all === 'object' ? all : {};
  } catch {
    return {};
  }
}

function saveAll(all) {
  try {
    localStorage.setItem(KEY, JSON.stringify(all));
  } catch {
    // Private browsing or storage full: the pairing works for this visit.
  }
}

// {token, fingerprint, name, url} of the pairing URL this page was opened
// with (`url` as it came, for screen_name.js to carry to the name), or null: read by the protocol's one codec (pointer.js, the WebAssembly
// module) as the pairing URL of this host with the fragment, whatever
// scheme, path or options the page itself was opened with (a page reached
// over plain http still pairs, and then offers photos).
async function freshPairing(location) {
  if (!/(^#|&)t=/.test(location.hash)) return null;
  try {
    const url = `https://${location.host}/${location.hash}`;
    const { token, fingerprint, name } = await parsePairingUrl(url);
    return { token, fingerprint, name: name || undefined, url };
  } catch {
    return null;
  }
}

// The pairing for this page: a fresh one from the fragment (kept, and the
// fragment removed), else the one kept for this origin, else null.
export async function currentPairing(location = window.location) {
  const fresh = await freshPairing(location);
  const all = loadAll();
  if (fresh) {
    all[location.origin] = { ...all[location.origin], ...fresh, pairedAt: Date.now() };
    saveAll(all);
    history.replaceState(null, '', location.pathname + location.search);
    return { ...all[location.origin], origin: location.origin, fresh: true };
  }
  const kept = all[location.origin];
  return kept && kept.token ? { ...kept, origin: location.origin } : null;
}

// Adds `fields` to the pairing kept for `origin` (the provider's name, when
// the screen's .local name was last tried).
export function rememberAbout(origin, fields) {
  const all = loadAll();
  if (!all[origin]) return;
  Object.assign(all[origin], fields);
  saveAll(all);
}

export function forget(origin) {
  const all = loadAll();
  delete all[origin];
  saveAll(all);
}
