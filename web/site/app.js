// The phone page: point the camera at a screen showing the field, see what
// is under the crosshair, take it. The detector runs in worker.js; the
// messages travel over transport.js; the pairing comes from the QR code's
// URL (pairing.js). docs/PROTOCOL.md has the messages.
import { connect } from './transport.js';
import { currentPairing, forget, rememberProviderName } from './pairing.js';
import { Sha256 } from './sha256.js';

const $ = (id) => document.getElementById(id);
const params = new URLSearchParams(location.search);
const options = {
  autograb: params.get('autograb') === '1',
  transport: ['ws', 'http'].includes(params.get('transport')) ? params.get('transport') : undefined,
  photo: params.get('photo') === '1',
};
const CLIENT = `umf-web/0.1 (${navigator.userAgentData?.platform || navigator.platform || 'web'})`;
const STEADY_MS = 500;            // a lock this long, ...
const STEADY_MODULES = 0.5;       // ... moving less than this, is steady (as the native requester)
const HINT_AFTER_MS = 6000;       // searching this long: say how to help the detector
const GRAB_TIMEOUT_MS = 20000;
const HISTORY_KEY = 'umf.history.v1';
const HISTORY_MAX = 50;

const debug = { transport: null, frames: 0, locks: 0, firstLockMs: null, lastResult: null, detectMs: null };
window.umfDebug = debug;
const pageStart = performance.now();

let pairing = null;
let link = null;          // the transport
let welcome = null;
let worker = null;
let workerReady = false;
let stream = null;
let nextId = 1;
let lastAimAt = 0;
let lastSeekingAt = 0;
let aimInterval = 200;
let lock = null;          // {point, since, origin} while locked
let searchingSince = performance.now();
let pendingGrab = null;   // {id, timer}
let objectUrl = null;

// ---- state and words -------------------------------------------------------

function setState(state, status) {
  document.body.dataset.state = state;
  if (status !== undefined) $('status').textContent = status;
  $('grab').disabled = state !== 'locked';
  if (state !== 'locked' && state !== 'grabbing') $('target-title').textContent = '';
}

const ERRORS = {
  'camera-denied': ['Camera not allowed', 'This page needs the camera to see the screen. Allow the camera for this site in the browser\'s settings, then try again — or take a photo instead.'],
  'no-camera': ['No camera', 'No camera could be opened. If another app is using it, close that app — or take a photo instead.'],
  'insecure-context': ['Live camera not available here', 'The browser allows the live camera only on a secure (https) page. Take a photo of the screen instead.'],
  'unpaired': ['Not paired with a screen', 'Scan the QR code the screen shows (umf-provider prints it, and its tray menu shows it) to pair this phone.'],
  'token-rejected': ['This pairing is no longer valid', 'The screen did not accept this phone\'s pairing (it may have been renewed). Scan the screen\'s QR code again.'],
  'unreachable': ['Cannot reach the screen', 'The screen\'s computer did not answer. Check that the phone is on the same network and that umf-provider is running, then try again.'],
  'protocol': ['Unexpected answer', 'The screen answered in a way this page does not understand. Update umf-provider or reload this page.'],
};

function showError(code, detail) {
  const [title, text] = ERRORS[code] || ['Something went wrong', ''];
  $('error').dataset.code = code;
  $('error-title').textContent = title;
  $('error-text').textContent = detail ? `${text} (${detail})` : text;
  // Only a new QR code helps an unpaired phone.
  $('error-retry').hidden = code === 'unpaired';
  $('error').hidden = false;
  setState('error', title);
}

function hideSheets() {
  for (const id of ['result', 'error', 'history', 'pairing']) $(id).hidden = true;
}

function hint(code, text) {
  const h = $('hint');
  if (!code) {
    h.hidden = true;
    delete h.dataset.code;
    return;
  }
  h.dataset.code = code;
  h.textContent = text;
  h.hidden = false;
}

// ---- connection -------------------------------------------------------------

function send(message) {
  link?.send({ v: 1, ...message });
}

function onMessage(message) {
  if (message.type === 'target') {
    if (document.body.dataset.state === 'locked') $('target-title').textContent = message.title || describeKind(message.kind);
  } else if (message.type === 'content') {
    if (pendingGrab && message.id === pendingGrab.id) finishGrab(message);
  } else if (message.type === 'error') {
    if (pendingGrab && message.id === pendingGrab.id) {
      clearTimeout(pendingGrab.timer);
      pendingGrab = null;
      showResult({ kind: 'none', title: message.code === 'not_found' ? 'No screen there' : 'Not taken',
                   detail: message.message });
    }
  }
}

function onClose(code) {
  link = null;
  if (code === 1012) {
    // The screen's layout changed: a new welcome brings the new field.
    start();
    return;
  }
  if (document.body.dataset.state !== 'error') showError('unreachable', `connection closed, code ${code}`);
}

function describeKind(kind) {
  return { url: 'A link', file: 'A file', snapshot: 'A picture of the screen', none: 'Nothing to take' }[kind] || '';
}

async function connectToProvider() {
  setState('connecting', 'Connecting to the screen…');
  const hello = { type: 'hello', v: 1, id: nextId++, token: pairing.token, client: CLIENT };
  try {
    link = await connect(hello, { prefer: options.transport, onMessage, onClose });
  } catch (e) {
    showError(e.code || 'unreachable', e.message);
    return false;
  }
  welcome = link.welcome;
  debug.transport = link.kind;
  aimInterval = 1000 / Math.min(5, welcome.limits?.aims_per_s || 5);
  rememberProviderName(pairing.origin, welcome.provider?.name);
  $('pairing-provider').textContent = welcome.provider?.name || '—';
  $('pairing-transport').textContent = link.kind === 'ws' ? 'secure WebSocket' : 'HTTPS requests';
  return true;
}

function startWorker() {
  return new Promise((resolve) => {
    worker?.terminate();
    workerReady = false;
    busy = false;  // a frame the old worker held is gone with it
    worker = new Worker(new URL('./worker.js', import.meta.url), { type: 'module' });
    worker.onmessage = (event) => {
      const m = event.data;
      if (m.type === 'ready') {
        workerReady = true;
        resolve(true);
      } else if (m.type === 'result') {
        onResult(m.result);
      } else if (m.type === 'still-result') {
        onStill(m.result);
      } else if (m.type === 'failure') {
        if (!workerReady) {
          showError('protocol', m.message);
          resolve(false);
        }
        busy = false;
      }
    };
    worker.onerror = (e) => {
      showError('protocol', `the detector did not start: ${e.message || 'worker error'}`);
      resolve(false);
    };
    worker.postMessage({ type: 'field', field: welcome.field.definition });
  });
}

// ---- camera -----------------------------------------------------------------

let busy = false;
let frameId = 0;

// No frames to the detector while a sheet asks for the user's attention: it
// saves the phone's battery, and nothing would be done with them.
const idle = () => ['result', 'error', 'unpaired'].includes(document.body.dataset.state);

async function startCamera() {
  setState('camera', 'Starting the camera…');
  if (!navigator.mediaDevices?.getUserMedia) {
    startPhotoMode(window.isSecureContext ? 'no-camera' : 'insecure-context');
    return;
  }
  try {
    stream = await navigator.mediaDevices.getUserMedia({
      audio: false,
      video: { facingMode: { ideal: 'environment' }, width: { ideal: 1280 }, height: { ideal: 720 } },
    });
  } catch (e) {
    const code = e.name === 'NotAllowedError' || e.name === 'SecurityError' ? 'camera-denied' : 'no-camera';
    showError(code, e.name);
    $('photo').hidden = false;
    return;
  }
  const track = stream.getVideoTracks()[0];
  // Continuous focus where the camera offers it: a fixed focus blurs the screen's modules.
  try {
    if (track.getCapabilities?.().focusMode?.includes('continuous'))
      await track.applyConstraints({ advanced: [{ focusMode: 'continuous' }] });
  } catch { /* not offered */ }
  const video = $('camera');
  video.srcObject = stream;
  await video.play().catch(() => {});
  searchingSince = performance.now();
  setState('searching', 'Point at the screen');
  if (typeof MediaStreamTrackProcessor !== 'undefined') pumpFrames(track);
  else pumpVideo(video);
}

// VideoFrames straight from the track, handed to the worker without a copy.
async function pumpFrames(track) {
  const reader = new MediaStreamTrackProcessor({ track }).readable.getReader();
  for (;;) {
    const { value: frame, done } = await reader.read();
    if (done) return;
    if (busy || !workerReady || pendingGrab || idle()) {
      frame.close();
      continue;
    }
    busy = true;
    worker.postMessage({ type: 'frame', id: ++frameId, frame }, [frame]);
  }
}

// Elsewhere: a bitmap of the video element per frame.
function pumpVideo(video) {
  const next = () => (video.requestVideoFrameCallback ? video.requestVideoFrameCallback(step) : requestAnimationFrame(step));
  const step = async () => {
    if (!busy && workerReady && !pendingGrab && !idle() && video.videoWidth > 0) {
      busy = true;
      try {
        const bitmap = await createImageBitmap(video);
        worker.postMessage({ type: 'frame', id: ++frameId, frame: bitmap }, [bitmap]);
      } catch {
        busy = false;
      }
    }
    if (stream) next();
  };
  next();
}

function onResult(r) {
  busy = false;
  debug.frames += 1;
  debug.lastResult = r;
  debug.detectMs = r.ms;
  if (pendingGrab || document.body.dataset.state === 'result' || document.body.dataset.state === 'error') return;
  const now = performance.now();
  if (r.state === 'locked' && r.point) {
    if (!lock) {
      debug.locks += 1;
      if (debug.firstLockMs === null) debug.firstLockMs = now - pageStart;
      lock = { point: r.point, since: now, origin: r.point };
      hint(null);
    }
    // Steady: the aim stayed within STEADY_MODULES since `since`.
    if (Math.hypot(r.point[0] - lock.origin[0], r.point[1] - lock.origin[1]) > STEADY_MODULES) {
      lock.origin = r.point;
      lock.since = now;
    }
    lock.point = r.point;
    if (document.body.dataset.state !== 'locked') setState('locked', 'Locked — tap Grab to take it');
    if (now - lastAimAt >= aimInterval) {
      lastAimAt = now;
      send({ type: 'aim', id: nextId++, point: r.point, confidence: r.confidence });
    }
    if (options.autograb && now - lock.since >= STEADY_MS) grab();
  } else {
    if (lock) {
      lock = null;
      searchingSince = now;
    }
    if (document.body.dataset.state !== 'searching') setState('searching', 'Point at the screen');
    if (now - lastSeekingAt >= 1000) {
      lastSeekingAt = now;
      send({ type: 'seeking' });
    }
    if (now - searchingSince > HINT_AFTER_MS)
      hint('detection-failing', 'No screen found yet — move closer, hold the phone still, and make sure the screen is bright enough.');
  }
}

// ---- grab ---------------------------------------------------------------------

function grab(point = lock?.point) {
  if (!point || pendingGrab || !link) return;
  const id = `g${nextId++}`;
  pendingGrab = {
    id,
    timer: setTimeout(() => {
      pendingGrab = null;
      showError('unreachable', 'the screen did not answer the grab');
    }, GRAB_TIMEOUT_MS),
  };
  setState('grabbing', 'Taking it…');
  send({ type: 'grab', id, point });
}

async function finishGrab(content) {
  clearTimeout(pendingGrab.timer);
  pendingGrab = null;
  if (content.kind === 'url') {
    showResult({ kind: 'url', title: content.title || content.url, url: content.url });
  } else if (content.kind === 'file' || content.kind === 'snapshot') {
    setState('grabbing', `Receiving ${content.name}…`);
    try {
      const bytes = await download(content);
      showResult({ kind: content.kind, title: content.title || content.name, file: content, bytes });
    } catch (e) {
      showResult({ kind: 'none', title: 'The transfer failed', detail: e.message });
    }
  } else {
    showResult({ kind: 'none', title: content.title || 'Nothing to take here' });
  }
}

async function download(content) {
  const response = await fetch(content.download, { cache: 'no-store' });
  if (!response.ok) throw new Error(`the download answered ${response.status}`);
  const total = content.size;
  const reader = response.body.getReader();
  const chunks = [];
  let received = 0;
  // Without crypto.subtle (a plain http page) the bytes are hashed as they come.
  const ownHash = content.sha256 && !crypto.subtle ? new Sha256() : null;
  for (;;) {
    const { value, done } = await reader.read();
    if (done) break;
    chunks.push(value);
    ownHash?.update(value);
    received += value.length;
    if (total > 0) $('status').textContent = `Receiving ${content.name}… ${Math.floor((100 * received) / total)} %`;
  }
  if (received !== total) throw new Error(`${received} of ${total} bytes arrived`);
  const blob = new Blob(chunks, { type: content.mime });
  let verified = null;
  if (content.sha256) {
    let hex;
    if (ownHash) {
      hex = ownHash.hex();
    } else {
      const digest = new Uint8Array(await crypto.subtle.digest('SHA-256', await blob.arrayBuffer()));
      hex = Array.from(digest, (b) => b.toString(16).padStart(2, '0')).join('');
    }
    if (hex !== content.sha256) throw new Error('the file arrived changed (SHA-256 differs)');
    verified = true;
  }
  return { blob, verified };
}

function formatSize(n) {
  if (n < 1024) return `${n} B`;
  if (n < 1024 * 1024) return `${(n / 1024).toFixed(1)} KB`;
  return `${(n / 1024 / 1024).toFixed(1)} MB`;
}

function showResult({ kind, title, url, file, bytes, detail }) {
  const sheet = $('result');
  for (const key of ['url', 'name', 'size', 'sha256', 'verified']) delete sheet.dataset[key];
  sheet.dataset.kind = kind;
  sheet.dataset.title = title || '';
  $('result-title').textContent = title || describeKind(kind);
  $('result-detail').textContent = detail || '';
  $('result-preview').replaceChildren();
  $('result-open').hidden = $('result-save').hidden = true;
  if (objectUrl) URL.revokeObjectURL(objectUrl);
  objectUrl = null;
  if (kind === 'url') {
    sheet.dataset.url = url;
    $('result-detail').textContent = url;
    $('result-open').href = url;
    $('result-open').hidden = false;
  } else if (file && bytes) {
    Object.assign(sheet.dataset, { name: file.name, size: String(file.size) });
    if (file.sha256) sheet.dataset.sha256 = file.sha256;
    sheet.dataset.verified = bytes.verified ? 'true' : 'false';
    $('result-detail').textContent = `${file.name} · ${formatSize(file.size)}${bytes.verified ? ' · checked' : ''}`;
    objectUrl = URL.createObjectURL(bytes.blob);
    $('result-save').href = objectUrl;
    $('result-save').download = file.name;
    $('result-save').hidden = false;
    if (file.mime.startsWith('image/')) {
      const img = document.createElement('img');
      img.src = objectUrl;
      img.alt = file.name;
      $('result-preview').append(img);
    }
    if (file.mime.startsWith('image/') || file.mime === 'application/pdf') {
      $('result-open').href = objectUrl;
      $('result-open').hidden = false;
    }
  }
  if (kind !== 'none') remember({ kind, title, url, name: file?.name, size: file?.size, at: Date.now() });
  hideSheets();
  sheet.hidden = false;
  setState('result', kind === 'none' ? 'Nothing taken' : 'Taken');
}

// ---- history -------------------------------------------------------------------

function loadHistory() {
  try {
    return JSON.parse(localStorage.getItem(HISTORY_KEY) || '[]');
  } catch {
    return [];
  }
}

function remember(entry) {
  const list = [entry, ...loadHistory()].slice(0, HISTORY_MAX);
  try {
    localStorage.setItem(HISTORY_KEY, JSON.stringify(list));
  } catch { /* storage full: the history is a convenience */ }
}

function showHistory() {
  const list = loadHistory();
  const ol = $('history-list');
  ol.replaceChildren(...list.map((e) => {
    const li = document.createElement('li');
    if (e.kind === 'url') {
      const a = document.createElement('a');
      a.href = e.url;
      a.target = '_blank';
      a.rel = 'noopener noreferrer';
      a.textContent = e.title || e.url;
      li.append(a);
    } else {
      li.textContent = `${e.title || e.name}${e.size ? ` (${formatSize(e.size)})` : ''}`;
    }
    const when = document.createElement('small');
    when.textContent = ` — ${new Date(e.at).toLocaleString()}`;
    li.append(when);
    return li;
  }));
  $('history-empty').hidden = list.length > 0;
  $('history').hidden = false;
}

// ---- photo mode ----------------------------------------------------------------

function startPhotoMode(reason) {
  $('photo').hidden = false;
  $('camera').hidden = true;
  setState('photo', 'Take a photo of the screen');
  if (reason) hint(reason, ERRORS[reason][1]);
}

async function onPhoto(file) {
  if (!file || !workerReady) return;
  setState('grabbing', 'Looking for the screen in the photo…');
  try {
    const bitmap = await createImageBitmap(file);
    worker.postMessage({ type: 'still', id: ++frameId, bitmap }, [bitmap]);
  } catch (e) {
    showResult({ kind: 'none', title: 'That picture could not be read', detail: e.message });
  }
}

function onStill(r) {
  const point = r && r.found ? r.point || r.rawPoint : null;
  if (!point) {
    showResult({ kind: 'none', title: 'No screen found in the photo',
                 detail: 'Take it closer and straight on, with the whole crosshair area on the screen.' });
    return;
  }
  if (debug.firstLockMs === null) debug.firstLockMs = performance.now() - pageStart;
  debug.locks += 1;
  send({ type: 'aim', id: nextId++, point, confidence: r.confidence });
  grab(point);
}

// ---- start -------------------------------------------------------------------------

async function start() {
  hideSheets();
  hint(null);
  pairing = currentPairing();
  $('pairing-origin').textContent = location.origin;
  $('pairing-fingerprint').textContent = pairing?.fingerprint || '—';
  if (!pairing) {
    showError('unpaired');
    setState('unpaired', 'Not paired');
    return;
  }
  if (!(await connectToProvider())) return;
  if (!(await startWorker())) return;
  if (stream) {
    setState('searching', 'Point at the screen');
    return;
  }
  if (options.photo || !window.isSecureContext) startPhotoMode(window.isSecureContext ? null : 'insecure-context');
  else await startCamera();
}

$('grab').addEventListener('click', () => grab());
$('camera').addEventListener('click', () => document.body.dataset.state === 'locked' && grab());
$('result-close').addEventListener('click', () => {
  hideSheets();
  lock = null;
  searchingSince = performance.now();
  if (!link) start();
  else if (stream) setState('searching', 'Point at the screen');
  else startPhotoMode();
});
$('error-retry').addEventListener('click', () => {
  link?.close();
  link = null;
  start();
});
$('photo-input').addEventListener('change', (e) => onPhoto(e.target.files?.[0]));
$('show-history').addEventListener('click', showHistory);
$('history-close').addEventListener('click', () => ($('history').hidden = true));
$('history-clear').addEventListener('click', () => {
  localStorage.removeItem(HISTORY_KEY);
  showHistory();
});
$('show-pairing').addEventListener('click', () => ($('pairing').hidden = false));
$('pairing-close').addEventListener('click', () => ($('pairing').hidden = true));
$('pairing-forget').addEventListener('click', () => {
  forget(location.origin);
  link?.close();
  link = null;
  stream?.getTracks().forEach((t) => t.stop());
  stream = null;
  hideSheets();
  showError('unpaired');
  setState('unpaired', 'Not paired');
});

start();
