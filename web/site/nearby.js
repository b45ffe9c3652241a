// Which other screen the camera sees, when it is not this page's own
// (docs/PROTOCOL.md, "Nearby screens"): the screen lists the screens
// announced near it (/nearby.json), each of which serves its field
// (ORIGIN/field.json). A field is fetched only where this phone's browser
// trusts that screen's certificate, that is where its root was installed,
// the first step of pairing with it; the detector's worker then tries each
// field on a frame of the camera. Exactly one that is found is offered as a
// link to that screen's page, where the phone's pairing with it lives. None,
// or two screens claiming one field, offer nothing (docs/SECURITY.md,
// "Nearby screens").
import { ANOTHER_SCREEN_HINT, DETECTION_HINT, hint, nearbyScreenHint } from './sheets.js';

const LIST_TTL_MS = 30000;      // the screen browses as often
const FETCH_TIMEOUT_MS = 3000;  // a screen's field, or its answer that it is not trusted
const IDENTIFY_EVERY_MS = 1500; // one frame for the other fields, at most this often

async function fetchJson(url, timeoutMs) {
  const abort = new AbortController();
  const timer = setTimeout(() => abort.abort(), timeoutMs);
  try {
    const response = await fetch(url, { cache: 'no-store', signal: abort.signal, credentials: 'omit' });
    if (!response.ok) throw new Error(`HTTP ${response.status}`);
    return await response.json();
  } finally {
    clearTimeout(timer);
  }
}

// A nearby screen's page: https, a .local host, a port, nothing more.
function pageOrigin(origin) {
  try {
    const u = new URL(origin);
    return u.protocol === 'https:' && /\.local$/.test(u.hostname) && u.port && u.origin === origin ? u.origin : null;
  } catch {
    return null;
  }
}

// worker: the detector's; debug: window.umfDebug, whose `nearby` shows the
// state (listed, fetched, tried, match) to tests and to people debugging.
export function createNearby(worker, debug) {
  let screens = [];        // {name, origin}, the fields the worker holds, in its order
  let listedAt = -Infinity;
  let loading = null;      // the list and fields being fetched
  let identifying = false;
  let lastTry = -Infinity;
  let match = null;        // {name, origin} of the one screen found in the last frame tried
  let misses = 0;          // tries in a row that found no field
  debug.nearby = { listed: 0, fetched: 0, tried: 0, found: [], match: null, failure: null };

  async function load() {
    try {
      const list = await fetchJson('/nearby.json', FETCH_TIMEOUT_MS);
      const candidates = (Array.isArray(list?.screens) ? list.screens : [])
        .filter((s) => typeof s?.name === 'string' && pageOrigin(s.origin) && s.origin !== location.origin);
      debug.nearby.listed = candidates.length;
      const fetched = await Promise.all(candidates.map((s) =>
        fetchJson(`${s.origin}/field.json`, FETCH_TIMEOUT_MS)
          .then((field) => ({ name: s.name, origin: s.origin, field }))
          .catch(() => null)));  // not trusted, gone, or not answering: not offered
      const usable = fetched.filter(Boolean);
      debug.nearby.fetched = usable.length;
      screens = usable.map(({ name, origin }) => ({ name, origin }));
      worker.postMessage({ type: 'nearby-fields', fields: usable.map((s) => s.field) });
      debug.nearby.failure = null;
    } catch (e) {
      debug.nearby.failure = String(e?.message || e);
      screens = [];
      worker.postMessage({ type: 'nearby-fields', fields: [] });
    }
    listedAt = performance.now();
    loading = null;
  }

  return {
    // The core's view: while it says another screen, the list is kept fresh.
    viewed(view) {
      if (!view?.another_screen) {
        match = null;
        misses = 0;
        debug.nearby.match = null;
        return;
      }
      if (!loading && performance.now() - listedAt > LIST_TTL_MS) loading = load();
    },
    // Whether the next camera frame goes to the other screens' fields; if
    // so, it is counted as sent.
    takesFrame(view) {
      const wanted = !!view?.another_screen && !loading && !identifying && screens.length > 0 &&
                     performance.now() - lastTry > IDENTIFY_EVERY_MS;
      if (wanted) {
        identifying = true;
        lastTry = performance.now();
      }
      return wanted;
    },
    // The worker's answer: the indices of the fields found in the frame. One
    // frame that finds none (blurred, half off the screen) keeps the last
    // answer, a second one in a row withdraws it (the camera may have moved
    // on to a screen not listed); two fields at once withdraw it at once.
    identified(found) {
      identifying = false;
      debug.nearby.tried += 1;
      debug.nearby.found = found.map((i) => screens[i]?.name);
      misses = found.length === 0 ? misses + 1 : 0;
      if (found.length === 1 && screens[found[0]]) match = screens[found[0]];
      else if (found.length > 1 || misses >= 2) match = null;
      debug.nearby.match = match;
    },
    // The worker could not read the frame.
    failed() {
      identifying = false;
    },
    match: () => match,
    // The searching view's hint: another screen, and which one when found.
    showHint(view) {
      this.viewed(view);
      if (!view.another_screen) hint(view.hint ? 'detection-failing' : null, DETECTION_HINT);
      else if (match) hint('another-screen', nearbyScreenHint(match.name), { href: `${match.origin}/`, text: 'open its page' });
      else hint('another-screen', ANOTHER_SCREEN_HINT);
    },
  };
}
