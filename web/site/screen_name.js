// The screen's .local name (the pairing URL's n=), where a phone keeps
// finding the screen after its address changed (a new DHCP lease, another
// network). The QR code names the address, which every phone can open; a
// page opened there moves once to https://NAME.local:PORT/, carrying the
// pairing in the fragment as the QR code did, when both hold:
// - this phone trusts the screen's root: its service worker registered,
//   which browsers allow only on a trusted certificate. A phone that only
//   clicked through the warning would meet it again at the name, so it
//   stays at the address, as before;
// - the name answers from here (a request the browser makes with its own
//   name resolution and certificate checks; it fails on either).
// From then on the page, its pairing, its history and an installed app all
// live at the name. A name that did not answer is tried again on a fresh
// pairing, else after an hour: a phone that cannot resolve .local names
// (older Android) should not wait on it each time the page opens.
import { rememberAbout } from './pairing.js';

const REACH_TIMEOUT_MS = 2500;
const RETRY_AFTER_MS = 60 * 60 * 1000;

// https://NAME:PORT of the pairing's name, or null when the page is there
// already, the screen has no name, or the page is not on https.
export function nameOrigin(pairing, location) {
  if (!pairing?.name || !pairing.url || location.protocol !== 'https:') return null;
  if (location.hostname.toLowerCase() === pairing.name.toLowerCase()) return null;
  return `https://${pairing.name}${location.port ? `:${location.port}` : ''}`;
}

// Whether `origin` answers over a certificate this browser trusts. The
// answer's body is opaque (no CORS) and not needed: a failed name lookup,
// connection or certificate check rejects.
export async function answers(origin) {
  const controller = new AbortController();
  const timer = setTimeout(() => controller.abort(), REACH_TIMEOUT_MS);
  try {
    await fetch(`${origin}/manifest.webmanifest`, { mode: 'no-cors', cache: 'no-store', credentials: 'omit',
                                                   signal: controller.signal });
    return true;
  } catch {
    return false;
  } finally {
    clearTimeout(timer);
  }
}

// Moves the page to the screen's name when it should (see above); true when
// it is leaving. `trust`: registerServiceWorker's promise. `debug.name`
// records what was decided, for the tests.
export async function moveToName(pairing, location, trust, debug) {
  const origin = nameOrigin(pairing, location);
  if (!origin) return false;
  if (!pairing.fresh && Date.now() - (pairing.nameTriedAt ?? 0) < RETRY_AFTER_MS) {
    debug.name = { origin, tried: 'lately' };
    return false;
  }
  const trusted = (await trust) === 'active';
  const reached = trusted && (await answers(origin));
  debug.name = { origin, trusted, reached };
  if (!reached) {
    if (trusted) rememberAbout(pairing.origin, { nameTriedAt: Date.now() });
    return false;
  }
  location.replace(`${origin}${location.pathname}${location.search}${new URL(pairing.url).hash}`);
  return true;
}
