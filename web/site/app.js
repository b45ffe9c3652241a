// The phone page: point the camera at a screen showing the field, see what
// is under the crosshair, take it. The detector runs in worker.js; the
// messages travel over transport.js; the pairing comes from the QR code's
// URL (pairing.js). docs/PROTOCOL.md has the messages. Put mode goes the
// other way: a file, a photo or a link from the phone (or from its carry
// list, carry.js) to the place on the screen it points at.
import { connect } from './transport.js';
import { carry, getCarried, listCarried, noteFile, removeCarried } from './carry.js';
import { currentPairing, forget, rememberProviderName } from './pairing.js';
import { Sha256 } from './sha256.js';

const $ = (id) => document.getElementById(id);
const params = new URLSearchParams(location.search);
const options = {
  autograb: params.get('autograb') === '1',
  autoput: params.get('autoput') === '1',
  transport: ['ws', 'http'].includes(params.get('transport')) ? params.get('transport') : undefined,
  photo: params.get('photo') === '1',
};
const STEADY_MS = 500;            // a lock this long, ...
const STEADY_MODULES = 0.5;       // ... moving less than this, is steady (as the native requester)
const HINT_AFTER_MS = 6000;       // searching this long: say how to help the detector
const GRAB_TIMEOUT_MS = 20000;
const HISTORY_KEY = 'umf.history.v1';
const HISTORY_MAX = 50;
const DEVICE_KEY = 'umf.device.v1';
const PUT_REPLY_MS = 15000;        // the put's first answer, and the screen's after the upload
const PUT_ASKING_S = 30;           // the screen's answer_timeout: it refuses by itself after this
const PUT_ASKING_MS = (PUT_ASKING_S + 10) * 1000;
const PUT_TITLE_MAX = 512;

const debug = { transport: null, frames: 0, locks: 0, firstLockMs: null, lastResult: null, detectMs: null,
                device: null, client: null, features: [], serviceWorker: null, share: null, put: null };
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
let pendingGrab = null;   // {id, timer, receiving}: from the tap on Grab to its result
let objectUrl = null;
let mode = 'grab';        // 'put' while aiming a chosen thing at the screen
let putItem = null;       // what Put mode gives the screen: {kind: 'url', url, title} or
                          // {kind: 'file', blob, name, mime, size, title, sha256?, carriedId?}
let pendingPut = null;    // {id, timer, xhr, status}

// ---- state and words -------------------------------------------------------

function setState(state, status) {
  document.body.dataset.state = state;
  if (status !== undefined) $('status').textContent = status;
  $('grab').disabled = state !== 'locked';
  if (state !== 'locked' && state !== 'grabbing') $('target-title').textContent = '';
}

// The states in which camera frames are not looked at and the aim is not
// followed: a sheet asks for the user's attention.
const PAUSED = ['result', 'error', 'unpaired', 'put-choose', 'putting', 'put-result'];
const paused = () => PAUSED.includes(document.body.dataset.state);

function setMode(m) {
  mode = m;
  document.body.dataset.mode = m;
  $('grab').textContent = m === 'put' ? 'Put' : 'Grab';
  $('put-bar').hidden = m !== 'put';
  if (m === 'put') $('target-title').textContent = '';
  if (m === 'put' && putItem) {
    $('put-bar-what').textContent = putItem.kind === 'url' ? putItem.url
      : `${putItem.name} · ${formatSize(putItem.size)}`;
  }
}

function aimingStatus() {
  return mode === 'put' ? 'Point at where it should go' : 'Point at the screen';
}
function lockedStatus() {
  return mode === 'put' ? 'Locked — tap Put to give it to the screen' : 'Locked — tap Grab to take it';
}

const ERRORS = {
  'camera-denied': ['Camera not allowed', 'This page needs the camera to see the screen. Allow the camera for this site in the browser\'s settings, then try again — or take a photo instead.'],
  'no-camera': ['No camera', 'No camera could be opened. If another app is using it, close that app — or take a photo instead.'],
  'insecure-context': ['Live camera not available here', 'The browser allows the live camera only on a secure (https) page. Take a photo of the screen instead.'],
  'unpaired': ['Not paired with a screen', 'Scan the QR code the screen shows (umf-provider prints it, and its tray menu shows it) to pair this phone.'],
  'token-rejected': ['Not paired with this screen', 'The screen does not know this phone\'s pairing code: it belongs to another screen, or this screen made a new one. Scan the QR code the screen shows now.'],
  'unreachable': ['Cannot reach the screen', 'The screen\'s computer did not answer. Check that the phone is on the same network and that umf-provider is running, then try again.'],
  'protocol': ['Unexpected answer', 'The screen answered in a way this page does not understand. Update umf-provider or reload this page.'],
};

// What the screen (or the way there) said to a put, in plain words.
const PUT_ERRORS = {
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

function showError(code, detail) {
  const [title, text] = ERRORS[code] || ['Something went wrong', ''];
  $('error').dataset.code = code;
  $('error-title').textContent = title;
  $('error-text').textContent = detail ? `${text} (${detail})` : text;
  // Only a new QR code helps an unpaired phone, or one the screen does not know.
  $('error-retry').hidden = code === 'unpaired' || code === 'token-rejected';
  $('error').hidden = false;
  setState('error', title);
}

function hideSheets() {
  for (const id of ['result', 'error', 'history', 'pairing', 'put', 'put-status']) $(id).hidden = true;
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
  if (pendingPut && message.id === pendingPut.id && (message.type === 'put_status' || message.type === 'error')) {
    onPutMessage(message);
  } else if (message.type === 'target') {
    // In Put mode what lies there is not where the put goes (the screen keeps
    // it, or opens it there): the put bar names what is being put instead.
    if (document.body.dataset.state === 'locked' && mode === 'grab')
      $('target-title').textContent = message.title || describeKind(message.kind);
  } else if (message.type === 'content') {
    if (pendingGrab && !pendingGrab.receiving && message.id === pendingGrab.id) finishGrab(message);
  } else if (message.type === 'error') {
    if (pendingGrab && !pendingGrab.receiving && message.id === pendingGrab.id) {
      clearTimeout(pendingGrab.timer);
      pendingGrab = null;
      showResult({ kind: 'none', title: message.code === 'not_found' ? 'No screen there' : 'Not taken',
                   detail: message.message });
    }
  }
}

function onClose(code) {
  link = null;
  // A put under way can no longer hear its answer: it ends here, the error says why.
  cancelPut();
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
  const hello = { type: 'hello', v: 1, id: nextId++, token: pairing.token, client: await clientName(),
                  device: deviceName() };
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
  debug.features = Array.isArray(welcome.features) ? welcome.features : [];
  $('show-put').hidden = !debug.features.includes('put');
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
const idle = paused;

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
  setState('searching', aimingStatus());
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
  if (pendingGrab || pendingPut || paused()) return;
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
    if (document.body.dataset.state !== 'locked') setState('locked', lockedStatus());
    if (now - lastAimAt >= aimInterval) {
      lastAimAt = now;
      send({ type: 'aim', id: nextId++, point: r.point, confidence: r.confidence });
    }
    if (mode === 'put' && options.autoput && now - lock.since >= STEADY_MS) put();
    else if (mode === 'grab' && options.autograb && now - lock.since >= STEADY_MS) grab();
  } else {
    if (lock) {
      lock = null;
      searchingSince = now;
    }
    if (document.body.dataset.state !== 'searching') setState('searching', aimingStatus());
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
  // The grab lasts until its result shows: while a file arrives no frame is
  // looked at, Grab stays off and a second tap starts nothing.
  pendingGrab.receiving = true;
  try {
    await showGrabbed(content);
  } finally {
    pendingGrab = null;
  }
}

async function showGrabbed(content) {
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
  if (!response.ok) {
    // The provider says why in its error envelope (docs/PROTOCOL.md, "Errors over HTTP").
    const answer = await response.json().catch(() => null);
    const error = answer?.messages?.length === 1 && answer.messages[0]?.type === 'error' ? answer.messages[0] : null;
    throw new Error(error?.message || `the download answered ${response.status}`);
  }
  const total = content.size;
  const reader = response.body.getReader();
  const chunks = [];
  let received = 0;
  // Without crypto.subtle (a plain http page) the bytes are hashed as they come.
  const ownHash = content.sha256 && !crypto.subtle ? new Sha256() : null;
  const cut = () => new Error(`the transfer was cut after ${received} of ${total} bytes, so its SHA-256 could not ` +
                              'be checked and nothing was kept (a file changed on the screen since the grab is cut so)');
  for (;;) {
    let part;
    try {
      part = await reader.read();
    } catch {
      throw cut();
    }
    const { value, done } = part;
    if (done) break;
    chunks.push(value);
    ownHash?.update(value);
    received += value.length;
    if (total > 0) $('status').textContent = `Receiving ${content.name}… ${Math.floor((100 * received) / total)} %`;
  }
  if (received !== total) throw cut();
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
  // On the carry list, to be put on a screen later: links, and files whose bytes arrived whole.
  if (kind === 'url') keepCarried({ kind: 'url', url, title });
  else if (file && bytes) keepCarried({ kind: 'file', title, name: file.name, mime: file.mime, blob: bytes.blob,
                                        sha256: bytes.verified ? file.sha256 : undefined });
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
  if (mode === 'put') put(point);
  else grab(point);
}

// ---- put ---------------------------------------------------------------------------

// What the screen calls this phone (its console, the put prompt's "from"):
// the model where the browser tells it ("Pixel 7 (umf web, Android)"), else
// the kind of device ("iPhone (umf web, iOS)", "Linux (umf web)").
async function clientName() {
  const ua = navigator.userAgent;
  let model = '';
  try {
    model = (await navigator.userAgentData?.getHighEntropyValues?.(['model']))?.model || '';
  } catch { /* not told: from the user agent below */ }
  // Android user agents name the model after the version, unless reduced to "K".
  const android = /Android [\d.]+; ([^;)]+)[;)]/.exec(ua);
  if (!model && android && android[1].trim() !== 'K') model = android[1].trim();
  if (!model) model = /iPad/.test(ua) ? 'iPad' : /iPhone/.test(ua) ? 'iPhone' : '';
  const platform = navigator.userAgentData?.platform ||
    (/Android/.test(ua) ? 'Android' : /iPhone|iPad/.test(ua) ? 'iOS' : navigator.platform || '');
  const name = model ? `${model} (umf web${platform ? `, ${platform}` : ''})` : `${platform || 'Browser'} (umf web)`;
  debug.client = name.replace(/[^\x20-\x7e]/g, '?').slice(0, 100);
  return debug.client;
}

// The name this phone gives itself in every hello, so that the person at the
// screen can accept its puts "always": random, made once, kept. Printable
// ASCII, as the protocol asks.
function deviceName() {
  let name = null;
  try {
    name = localStorage.getItem(DEVICE_KEY);
  } catch { /* no storage: a name for this visit */ }
  if (!name || !/^[\x21-\x7e]{1,64}$/.test(name)) {
    const bytes = crypto.getRandomValues(new Uint8Array(8));
    name = `umf-web-${Array.from(bytes, (b) => b.toString(16).padStart(2, '0')).join('')}`;
    try {
      localStorage.setItem(DEVICE_KEY, name);
    } catch { /* as above */ }
  }
  debug.device = name;
  return name;
}

async function keepCarried(entry) {
  try {
    await carry(entry);
  } catch (e) {
    // Without IndexedDB (private browsing) the carry list stays empty.
    debug.carryError = e.message;
  }
}

// A file name as the protocol takes it: 1..255 bytes, no slashes, no control characters.
function cleanName(name) {
  let n = String(name || '').replace(/[\u0000-\u001f\u007f/\\]/g, '_').trim();
  if (!n || n === '.' || n === '..') n = 'file';
  const bytes = new TextEncoder();
  while (bytes.encode(n).length > 255) n = n.slice(0, -1);
  return n;
}

function cleanMime(mime) {
  return /^[\x21-\x7e][\x20-\x7e]{2,254}$/.test(mime || '') ? mime : 'application/octet-stream';
}

function clip(text, max) {
  let t = String(text || '');
  const bytes = new TextEncoder();
  while (bytes.encode(t).length > max) t = t.slice(0, -1);
  return t;
}

function validUrl(text) {
  try {
    const u = new URL(String(text).trim());
    return (u.protocol === 'http:' || u.protocol === 'https:') && u.href.length <= 8192 ? u.href : null;
  } catch {
    return null;
  }
}

async function sha256Hex(blob) {
  // crypto.subtle takes the whole file at once; it is there on every https page.
  if (crypto.subtle && blob.size <= 512 * 1024 * 1024) {
    const digest = new Uint8Array(await crypto.subtle.digest('SHA-256', await blob.arrayBuffer()));
    return Array.from(digest, (b) => b.toString(16).padStart(2, '0')).join('');
  }
  const hash = new Sha256();
  const step = 4 * 1024 * 1024;
  for (let at = 0; at < blob.size; at += step) hash.update(new Uint8Array(await blob.slice(at, at + step).arrayBuffer()));
  return hash.hex();
}

function fileItem(blob, { name, title, mime, sha256, carriedId } = {}) {
  const item = { kind: 'file', blob, name: cleanName(name ?? blob.name), mime: cleanMime(mime ?? blob.type),
                 size: blob.size, title: title || name || blob.name || '', carriedId };
  // Hashed while the user aims; the put waits for it if need be.
  item.sha256 = sha256 ? Promise.resolve(sha256) : sha256Hex(blob);
  item.sha256.catch(() => {});
  return item;
}

// Put mode with `item`: aim as for a grab, then Put.
function enterPut(item) {
  putItem = item;
  debug.put = { kind: item.kind, name: item.name, size: item.size, url: item.url, status: 'aiming' };
  hideSheets();
  hint(null);
  setMode('put');
  lock = null;
  searchingSince = performance.now();
  if (!link || !workerReady) return;  // start() brings the camera up, in Put mode
  if (stream) setState('searching', aimingStatus());
  else startPhotoMode();
}

function leavePut() {
  cancelPut();
  putItem = null;
  debug.put = null;
  hideSheets();
  setMode('grab');
  lock = null;
  searchingSince = performance.now();
  if (!link) start();
  else if (stream) setState('searching', aimingStatus());
  else startPhotoMode();
}

function cancelPut() {
  if (!pendingPut) return;
  clearTimeout(pendingPut.timer);
  pendingPut.xhr?.abort();
  pendingPut = null;
}

async function showPutChooser() {
  hideSheets();
  $('put-url-error').hidden = true;
  $('put').hidden = false;
  setState('put-choose', 'Choose what to put on the screen');
  await showCarried();
}

async function showCarried() {
  let items = [];
  try {
    items = await listCarried();
  } catch (e) {
    debug.carryError = e.message;
  }
  const ol = $('carry-list');
  ol.replaceChildren(...items.map((e) => {
    const li = document.createElement('li');
    li.dataset.id = String(e.id);
    li.dataset.kind = e.kind;
    if (e.kind === 'url') li.dataset.url = e.url;
    else Object.assign(li.dataset, { name: e.name, size: String(e.size) });
    const put = document.createElement('button');
    put.type = 'button';
    put.className = 'carry-put';
    put.textContent = e.kind === 'url' ? (e.title || e.url) : `${e.name} · ${formatSize(e.size)}`;
    put.addEventListener('click', () => enterPut(carriedItem(e)));
    const remove = document.createElement('button');
    remove.type = 'button';
    remove.className = 'carry-remove';
    remove.textContent = 'Remove';
    remove.setAttribute('aria-label', `Remove ${e.kind === 'url' ? e.url : e.name}`);
    remove.addEventListener('click', async () => {
      await removeCarried(e.id).catch(() => {});
      showCarried();
    });
    li.append(put, remove);
    return li;
  }));
  $('carry-empty').hidden = items.length > 0;
}

function carriedItem(e) {
  return e.kind === 'url' ? { kind: 'url', url: e.url, title: e.title, carriedId: e.id }
    : fileItem(e.blob, { name: e.name, title: e.title, mime: e.mime, sha256: e.sha256, carriedId: e.id });
}

function showPutStatus(status, title, text, { code, progress, outcome, name } = {}) {
  const sheet = $('put-status');
  for (const key of ['code', 'outcome', 'name']) delete sheet.dataset[key];
  sheet.dataset.status = status;
  if (code) sheet.dataset.code = code;
  if (outcome) sheet.dataset.outcome = outcome;
  if (name) sheet.dataset.name = name;
  $('put-status-title').textContent = title;
  $('put-status-text').textContent = text || '';
  $('put-progress').hidden = progress === undefined;
  if (progress !== undefined) $('put-progress').value = progress;
  const over = status === 'done' || status === 'error';
  $('put-again').hidden = !over || status === 'done' || !putItem;
  $('put-finish').hidden = !over;
  $('put-abort').hidden = over;
  if (debug.put) Object.assign(debug.put, { status, code: code ?? null, outcome: outcome ?? null, name: name ?? null });
  hideSheets();
  sheet.hidden = false;
  setState(over ? 'put-result' : 'putting', title);
}

function failPut(code, detail) {
  if (!pendingPut && !code.startsWith('share-')) return;
  cancelPut();
  const [title, text] = PUT_ERRORS[code] || ['Not put', ''];
  showPutStatus('error', title, detail && !PUT_ERRORS[code] ? `${text} (${detail})` : text, { code });
}

function armPutTimer(ms, why) {
  clearTimeout(pendingPut.timer);
  pendingPut.timer = setTimeout(() => failPut('unreachable', why), ms);
}

async function put(point = lock?.point) {
  if (!point || pendingPut || pendingGrab || !link || !putItem) return;
  const item = putItem;
  const id = `p${nextId++}`;
  pendingPut = { id, timer: null, xhr: null, status: 'sending' };
  const message = { type: 'put', id, point, kind: item.kind };
  if (item.title) message.title = clip(item.title, PUT_TITLE_MAX);
  if (item.kind === 'url') {
    message.url = item.url;
  } else {
    showPutStatus('hashing', 'Checking the file…', `${item.name} · ${formatSize(item.size)}`);
    try {
      message.sha256 = await item.sha256;
    } catch (e) {
      failPut('unreadable', e.message);
      return;
    }
    if (pendingPut?.id !== id) return;  // cancelled meanwhile
    Object.assign(message, { name: item.name, mime: item.mime, size: item.size });
  }
  showPutStatus('sending', 'Giving it to the screen…', item.kind === 'url' ? item.url : item.name);
  armPutTimer(PUT_REPLY_MS, 'the screen did not answer the put');
  send(message);
}

function onPutMessage(m) {
  if (m.type === 'error') {
    failPut(m.code, m.message);
    return;
  }
  if (m.status === 'asking' && pendingPut.status !== 'asking') {
    pendingPut.status = 'asking';
    armPutTimer(PUT_ASKING_MS, 'the screen did not answer within its 30 s');
    const started = Date.now();
    const what = putItem?.kind === 'url' ? putItem.url : `${putItem?.name} (${formatSize(putItem?.size ?? 0)})`;
    const tick = () => {
      if (pendingPut?.status !== 'asking') return;
      const left = Math.max(0, PUT_ASKING_S - Math.floor((Date.now() - started) / 1000));
      $('put-status-text').textContent = `${what} — someone at the screen has ${left} s to accept it.`;
      setTimeout(tick, 1000);
    };
    showPutStatus('asking', 'Waiting for the screen to accept…', '');
    tick();
  } else if (m.status === 'upload' && pendingPut.status !== 'upload' && putItem?.kind === 'file') {
    pendingPut.status = 'upload';
    upload(m.upload);
  } else if (m.status === 'done') {
    finishPut(m);
  }
}

// The bytes go with XMLHttpRequest, the one browser API that reports an
// upload's progress; the browser sets Content-Length from the Blob.
function upload(path) {
  const item = putItem;
  if (typeof path !== 'string' || !path.startsWith('/') || path.startsWith('//')) {
    failPut('bad_request', 'the upload link is not a path');
    return;
  }
  clearTimeout(pendingPut.timer);
  const xhr = new XMLHttpRequest();
  pendingPut.xhr = xhr;
  const id = pendingPut.id;
  showPutStatus('upload', `Sending ${item.name}…`, `0 of ${formatSize(item.size)}`, { progress: 0 });
  xhr.upload.onprogress = (e) => {
    if (pendingPut?.id !== id) return;
    const total = e.lengthComputable ? e.total : item.size;
    $('put-progress').value = total > 0 ? e.loaded / total : 1;
    $('put-status-text').textContent = `${formatSize(e.loaded)} of ${formatSize(total)}`;
  };
  xhr.onload = () => {
    if (pendingPut?.id !== id) return;
    let answer = null;
    try {
      answer = JSON.parse(xhr.responseText);
    } catch { /* not JSON: judged by the status below */ }
    // An error comes as the HTTPS transport's envelope (docs/PROTOCOL.md, "Errors over HTTP").
    const error = answer?.messages?.length === 1 && answer.messages[0]?.type === 'error' ? answer.messages[0] : null;
    if (xhr.status === 200 && answer?.type === 'put_status' && answer.status === 'done') finishPut(answer);
    else if (error) failPut(error.code === 'bad_request' ? 'interrupted' : error.code, error.message);
    else if (xhr.status === 200) armPutTimer(PUT_REPLY_MS, 'the screen did not confirm the upload');
    else failPut('interrupted', `the upload was answered ${xhr.status}`);
  };
  // The session usually says why first; this is for a connection that just broke.
  xhr.onerror = () => setTimeout(() => pendingPut?.id === id && failPut('interrupted', 'the connection broke'), 2000);
  xhr.open('PUT', path);
  xhr.send(item.blob);
}

function finishPut(m) {
  cancelPut();
  const what = putItem?.kind === 'url' ? 'The link' : putItem?.name || 'It';
  if (m.outcome === 'opened')
    showPutStatus('done', 'Opened on the screen', m.name ? `${m.name} was saved and opened.` : `${what} is open on the screen.`,
                  { outcome: 'opened', name: m.name });
  else
    showPutStatus('done', 'Saved on the screen', `Saved as ${m.name}.`, { outcome: 'saved', name: m.name });
}

// ?share=ID: the service worker (sw.js) took a share and carried it.
async function openShare(id) {
  params.delete('share');
  history.replaceState(null, '', location.pathname + (params.toString() ? `?${params}` : '') + location.hash);
  debug.share = { id };
  if (!/^\d+$/.test(id)) {
    const code = { unavailable: 'share-unavailable', empty: 'share-empty', 'too-large': 'share-too-large' }[id] || 'share-missing';
    failPut(code);
    return false;
  }
  let e = null;
  try {
    e = await getCarried(id);
  } catch (err) {
    debug.carryError = err.message;
  }
  if (!e) {
    failPut('share-missing');
    return false;
  }
  debug.share.kind = e.kind;
  enterPut(carriedItem(e));
  return true;
}

function registerServiceWorker() {
  if (!navigator.serviceWorker) {
    debug.serviceWorker = 'unsupported';
    return;
  }
  // A module worker, so that it shares carry.js with the page. Without it
  // (an untrusted certificate, an older browser) the page works the same,
  // only "Share → umf" does not.
  navigator.serviceWorker.register('sw.js', { type: 'module' }).then(
    () => navigator.serviceWorker.ready.then(() => { debug.serviceWorker = 'active'; }),
    (e) => { debug.serviceWorker = `not registered: ${e.message}`; });
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
    setState('searching', aimingStatus());
    return;
  }
  if (options.photo || !window.isSecureContext) startPhotoMode(window.isSecureContext ? null : 'insecure-context');
  else await startCamera();
}

const act = () => (mode === 'put' ? put() : grab());
$('grab').addEventListener('click', act);
$('camera').addEventListener('click', () => document.body.dataset.state === 'locked' && act());
$('result-close').addEventListener('click', () => {
  hideSheets();
  lock = null;
  searchingSince = performance.now();
  if (!link) start();
  else if (stream) setState('searching', aimingStatus());
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
$('show-put').addEventListener('click', showPutChooser);
$('put-close').addEventListener('click', leavePut);
$('put-cancel').addEventListener('click', leavePut);
$('put-finish').addEventListener('click', leavePut);
$('put-again').addEventListener('click', () => (putItem ? enterPut(putItem) : leavePut()));
$('put-abort').addEventListener('click', () => {
  cancelPut();
  enterPut(putItem);
});
for (const id of ['put-file', 'put-photo']) {
  $(id).addEventListener('change', (e) => {
    const file = e.target.files?.[0];
    e.target.value = '';  // choosing the same file again is a new choice
    if (file) enterPut(fileItem(file, { name: file.name || (id === 'put-photo' ? `photo-${Date.now()}.jpg` : 'file') }));
  });
}
$('put-url-form').addEventListener('submit', (e) => {
  e.preventDefault();
  const url = validUrl($('put-url').value);
  if (!url) {
    $('put-url-error').hidden = false;
    return;
  }
  enterPut({ kind: 'url', url, title: '' });
});
$('put-note-form').addEventListener('submit', (e) => {
  e.preventDefault();
  const text = $('put-note').value;
  if (!text.trim()) return;
  const note = noteFile(text);
  enterPut(fileItem(note.blob, { name: note.name, title: 'Note', mime: 'text/plain' }));
});
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

setMode('grab');
registerServiceWorker();
{
  const share = params.get('share');
  start().then(() => share && link && openShare(share));
}
