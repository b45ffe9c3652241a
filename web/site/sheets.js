// The page's states and sheets: the words for every error, the status line,
// the hint, which sheets show. No protocol rules here: what happens next is
// the requester core's (pointer.js), this only shows it.
export const $ = (id) => document.getElementById(id);

export function setState(state, status) {
  document.body.dataset.state = state;
  if (status !== undefined) $('status').textContent = status;
  $('grab').disabled = state !== 'locked';
  if (state !== 'locked' && state !== 'grabbing') $('target-title').textContent = '';
}

// The states in which camera frames are not looked at and the aim is not
// followed: a sheet asks for the user's attention.
const PAUSED = ['result', 'error', 'unpaired', 'put-choose', 'putting', 'put-result'];
export const paused = () => PAUSED.includes(document.body.dataset.state);

export const ERRORS = {
  'camera-denied': ['Camera not allowed', 'This page needs the camera to see the screen. Allow the camera for this site in the browser\'s settings, then try again — or take a photo instead.'],
  'no-camera': ['No camera', 'No camera could be opened. If another app is using it, close that app — or take a photo instead.'],
  'insecure-context': ['Live camera not available here', 'The browser allows the live camera only on a secure (https) page. Take a photo of the screen instead.'],
  'unpaired': ['Not paired with a screen', 'Scan the QR code the screen shows (umf-provider prints it, and its tray menu shows it) to pair this phone.'],
  'token-rejected': ['Not paired with this screen', 'The screen does not know this phone\'s pairing code: it belongs to another screen, or this screen made a new one. Scan the QR code the screen shows now.'],
  'unreachable': ['Cannot reach the screen', 'The screen\'s computer did not answer. Check that the phone is on the same network and that umf-provider is running, then try again.'],
  'protocol': ['Unexpected answer', 'The screen answered in a way this page does not understand. Update umf-provider or reload this page.'],
};

// What the screen (or the way there) said to a put, in plain words.
export const PUT_ERRORS = {
  'refused': ['The screen said no', 'The person at the screen dismissed it, or nobody answered within 30 seconds, or this screen takes nothing from phones.'],
  'too_large': ['Too large for the screen', 'The screen\'s computer has no room for a file this size.'],
  'interrupted': ['The transfer broke off', 'Nothing was kept on the screen. Try again.'],
  'not_found': ['No screen there', 'Point the crosshair at the screen, at the place where it should go, and try again.'],
  'bad_request': ['The screen could not read it', 'The screen did not understand what this page sent. Update umf-provider or reload this page.'],
  'rate_limited': ['Too many at once', 'Wait a moment, then try again.'],
  'unreachable': ['Cannot reach the screen', 'The screen\'s computer did not answer. Check that the phone is on the same network and that umf-provider is running.'],
  'unreadable': ['That file could not be read', 'The phone did not let this page read it. Choose it again.'],
  'share-unavailable': ['Sharing to umf is not set up yet', 'Open umf once from the screen\'s QR code (or the installed app), then share again.'],
  'share-empty': ['Nothing to put', 'What was shared holds no link or file. Share a link, a photo or a file.'],
  'share-too-large': ['Too large to carry', 'The shared file is larger than this phone keeps for umf (200 MB).'],
  'share-missing': ['The shared item is gone', 'It is no longer on this phone. Share it again.'],
  'internal': ['The screen had a problem', 'Something went wrong on the screen\'s computer. Try again.'],
};

export const DETECTION_HINT =
  'No screen found yet — move closer, hold the phone still, and make sure the screen is bright enough.';

// The camera sees a screen's field, but not this screen's: the phone is
// paired with another one (docs/ARCHITECTURE.md, "A field of its own").
export const ANOTHER_SCREEN_HINT =
  'This is another screen: scan its QR code to use it, or point at the screen this page belongs to.';
// ... and it is a screen nearby whose field this phone could fetch (nearby.js).
export const nearbyScreenHint = (name) => `This is another screen, ${name}:`;

export function showError(code, detail) {
  const [title, text] = ERRORS[code] || ['Something went wrong', ''];
  $('error').dataset.code = code;
  $('error-title').textContent = title;
  $('error-text').textContent = detail ? `${text} (${detail})` : text;
  // Only a new QR code helps an unpaired phone, or one the screen does not know.
  $('error-retry').hidden = code === 'unpaired' || code === 'token-rejected';
  $('error').hidden = false;
  setState('error', title);
}

export function hideSheets() {
  for (const id of ['result', 'error', 'history', 'pairing', 'put', 'put-status', 'trust']) $(id).hidden = true;
}

// link: {href, text}, a link after the text (a nearby screen's page). The
// same hint again leaves the element alone, so a tap on its link is not
// lost to the next frame's view.
export function hint(code, text, link = null) {
  const h = $('hint');
  if (!code) {
    h.hidden = true;
    delete h.dataset.code;
    return;
  }
  const href = link?.href ?? '';
  if (!h.hidden && h.dataset.code === code && h.dataset.text === text && (h.dataset.href ?? '') === href) return;
  h.dataset.code = code;
  h.dataset.text = text;
  h.textContent = text;
  if (link) {
    h.dataset.href = href;
    const a = document.createElement('a');
    a.id = 'hint-link';
    a.href = href;
    a.textContent = link.text;
    h.append(' ', a);
  } else {
    delete h.dataset.href;
  }
  h.hidden = false;
}

export function describeKind(kind) {
  return { url: 'A link', file: 'A file', snapshot: 'A picture of the screen', none: 'Nothing to take' }[kind] || '';
}

export function formatSize(n) {
  if (n < 1024) return `${n} B`;
  if (n < 1024 * 1024) return `${(n / 1024).toFixed(1)} KB`;
  if (n < 1024 * 1024 * 1024) return `${(n / 1024 / 1024).toFixed(1)} MB`;
  return `${(n / 1024 / 1024 / 1024).toFixed(1)} GB`;
}
