// The phone page: point the camera at a screen showing the field, see what
// is under the crosshair, take it; in Put mode, give the screen a file, a
// photo or a link at the place pointed at. The rules (when an aim is steady,
// how often to aim, what a grab or a put waits for and what each answer
// means) are the requester core's, the same C++ umf-requester runs, here as
// WebAssembly (pointer.js). This file wires the parts together: the core,
// the detector's worker (worker.js), the connection (transport.js), the
// pairing (pairing.js) and the views (sheets.js, camera.js, grab_result.js,
// put_view.js, history.js, trust.js) and the move to the screen's name
// (screen_name.js). docs/PROTOCOL.md has the messages.
import { openCamera, pumpFrames } from './camera.js';
import { download, showGrabOutcome, showResult } from './grab_result.js';
import { clearHistory, showHistory } from './history.js';
import { faintPulse } from './faint_pulse.js';
import { clientName, deviceName } from './identity.js';
import { currentPairing, forget, rememberAbout } from './pairing.js';
import { createPointer } from './pointer.js';
import { describeItem, sharedItem, showAskingCountdown, showPutChooser, showPutDone, showPutFailure, showPutStatus,
         upload, wirePutChoices } from './put_view.js';
import { createNearby } from './nearby.js';
import { moveToName } from './screen_name.js';
import { $, ERRORS, describeKind, formatSize, hideSheets, hint, paused, setState, showError } from './sheets.js';
import { connect } from './transport.js';
import { forPeople, registerServiceWorker, wireTrust } from './trust.js';

const params = new URLSearchParams(location.search);
const options = {
  autograb: params.get('autograb') === '1',
  autoput: params.get('autoput') === '1',
  transport: ['ws', 'http'].includes(params.get('transport')) ? params.get('transport') : undefined,
  photo: params.get('photo') === '1',
};
const TICK_MS = 250;  // the core's timeouts are looked at this often

const debug = { transport: null, pulse: null, frames: 0, locks: 0, firstFrameMs: null, firstLockMs: null, lastResult: null, detectMs: null,
                device: null, client: null, features: [], serviceWorker: null, share: null, put: null, view: null,
                name: null };
window.umfDebug = debug;
const pageStart = performance.now();

let pairing = null;
let link = null;          // the transport
let pointer = null;       // the requester core, one per welcome
let view = null;          // the core's last view
let worker = null;
let nearby = null;        // the other screens the camera may see (nearby.js), with the worker
let workerReady = false;
let busy = false;         // a frame is with the worker
let frameId = 0;
let stream = null;
let mode = 'grab';        // 'put' while aiming a chosen thing at the screen
let putItem = null;       // what Put mode gives the screen: {kind: 'url', url, title} or
                          // {kind: 'file', blob, name, mime, size, title, sha256 (a promise), carriedId?}
let grabbed = null;       // the grab's file bytes, once its download ended
let putXhr = null;        // the put's upload under way
let askingTimer = null;   // the countdown while the screen's person decides
let trust = null;         // registerServiceWorker's promise: whether this phone trusts the screen

// ---- the requester core --------------------------------------------------------

const seconds = () => performance.now() / 1000;

// Gives the core an event and carries out what it asks: the messages to
// send, a file to fetch, bytes to upload, a new connection; then shows its
// view. False when the core refused the event (a provider's message it
// cannot read, a put item it does not take: debug.refused says why).
function drive(event) {
  if (!pointer) return false;
  let answer;
  try {
    answer = pointer.event({ t: seconds(), ...event });
  } catch (e) {
    debug.refused = e.message;
    return false;
  }
  for (const message of answer.send) link?.send(message);
  if (answer.notice) debug.notice = answer.notice;
  render(answer.view);
  if (answer.download) receive(answer.download);
  if (answer.upload) sendPutFile(answer.upload);
  if (answer.reconnect) start();
  return true;
}

const aiming = (phase) => phase === 'searching' || phase === 'locked';

function render(next) {
  const was = view;
  view = next;
  debug.view = next;
  if (next.phase !== 'putting' || next.put !== 'asking') stopAskingCountdown();
  switch (next.phase) {
    case 'searching':
      if (was && !aiming(was.phase) && was.phase !== 'failed') backToAiming();
      else if (document.body.dataset.state === 'locked') setState('searching', aimingStatus());
      if (document.body.dataset.state === 'searching') nearby?.showHint(next);
      break;
    case 'locked':
      if (was?.phase !== 'locked') {
        debug.locks += 1;
        if (debug.firstLockMs === null) debug.firstLockMs = performance.now() - pageStart;
        hint(null);
      }
      // A sheet has the user (the put chooser, a result): an answer to an aim
      // sent before it opened must not take the page back to aiming.
      if (paused()) break;
      if (document.body.dataset.state !== 'locked') setState('locked', lockedStatus());
      // In Put mode what lies there is not where the put goes: the put bar names the item instead.
      $('target-title').textContent = mode === 'grab' && next.target
        ? next.target.title || describeKind(next.target.kind) : '';
      break;
    case 'grabbing':
      if (was?.phase !== 'grabbing') setState('grabbing', 'Taking it…');
      break;
    case 'putting':
      if (was?.phase !== 'putting' || was.put !== next.put) showPutProgress(next);
      break;
    case 'result':
      if (was?.phase !== 'result') showOutcome(next);
      break;
    case 'failed':
      if (was?.phase !== 'failed') {
        cancelUpload();
        showError(next.outcome?.code === 'unauthorized' ? 'token-rejected' : 'unreachable', next.outcome?.message);
      }
      break;
    default:
      break;
  }
}

function aimingStatus() {
  return mode === 'put' ? 'Point at where it should go' : 'Point at the screen';
}
function lockedStatus() {
  return mode === 'put' ? 'Locked — tap Put to give it to the screen' : 'Locked — tap Grab to take it';
}

// The core aims again after a result or a put: the camera, or a photo.
function backToAiming() {
  hideSheets();
  if (stream) setState('searching', aimingStatus());
  else if (link && workerReady) startPhotoMode();
}

function showOutcome(v) {
  if (v.mode === 'put') {
    cancelUpload();
    if (v.outcome.ok) showPutDone(v.outcome.put, putItem, debug);
    else showPutFailure(v.outcome.code, v.outcome.message, { item: putItem, debug });
  } else {
    showGrabOutcome(v.outcome, grabbed, debug);
    grabbed = null;
  }
}

// ---- connection -------------------------------------------------------------

function onMessage(message) {
  drive({ event: 'message', message });
}

function onClose(code) {
  link = null;
  if (!pointer) return;
  // The core says what comes of it: a new welcome for a changed screen, else an error.
  drive({ event: 'closed', code });
}

async function connectToProvider() {
  setState('connecting', 'Connecting to the screen…');
  debug.client = await clientName();
  debug.device = deviceName();
  const hello = { type: 'hello', v: 1, id: 1, token: pairing.token, client: debug.client, device: debug.device };
  try {
    link = await connect(hello, { prefer: options.transport, onMessage, onClose });
  } catch (e) {
    showError(e.code || 'unreachable', e.message);
    return false;
  }
  const welcome = link.welcome;
  debug.transport = link.kind;
  rememberAbout(pairing.origin, { provider: welcome.provider?.name });
  debug.features = Array.isArray(welcome.features) ? welcome.features : [];
  $('show-put').hidden = !debug.features.includes('put');
  $('pairing-provider').textContent = welcome.provider?.name || '—';
  $('pairing-transport').textContent = link.kind === 'ws' ? 'secure WebSocket' : 'HTTPS requests';
  pointer?.destroy();
  pointer = null;
  try {
    pointer = await createPointer({ welcome });
  } catch (e) {
    showError('protocol', e.message);
    return false;
  }
  view = null;
  drive({ event: 'auto', on: mode === 'put' ? options.autoput : options.autograb });
  if (mode === 'put' && putItem) choosePut(putItem);
  return true;
}

function startWorker() {
  return new Promise((resolve) => {
    worker?.terminate();
    workerReady = false;
    busy = false;  // a frame the old worker held is gone with it
    worker = new Worker(new URL('./worker.js', import.meta.url), { type: 'module' });
    nearby = createNearby(worker, debug);
    worker.onmessage = (event) => {
      const m = event.data;
      if (m.type === 'ready') {
        workerReady = true;
        resolve(true);
      } else if (m.type === 'result') {
        onResult(m.result);
      } else if (m.type === 'still-result') {
        onStill(m.result);
      } else if (m.type === 'identified') {
        busy = false;
        nearby.identified(m.found);
        if (view?.phase === 'searching' && document.body.dataset.state === 'searching') nearby.showHint(view);
      } else if (m.type === 'failure') {
        nearby.failed();
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
    debug.pulse = faintPulse(link.welcome.overlay);
    worker.postMessage({ type: 'field', field: link.welcome.field.definition, pulse: debug.pulse });
  });
}

// ---- camera and photos --------------------------------------------------------

// Frames go to the worker one at a time, and only while the core aims and no
// sheet has the user: nothing would be done with them, and it saves battery.
const framesWanted = () => !busy && workerReady && !paused() && (!view || aiming(view.phase));

function handFrame(frame) {
  busy = true;
  if (debug.firstFrameMs === null) debug.firstFrameMs = performance.now() - pageStart;
  // Now and then, while another screen is seen, a frame for the screens nearby.
  const frameRate = stream?.getVideoTracks()[0]?.getSettings().frameRate ?? 0;
  // When it was taken, for the pulse's fit: a VideoFrame's own time (microseconds), else now.
  const timeMs = typeof frame.timestamp === 'number' ? frame.timestamp / 1000 : performance.now();
  worker.postMessage({ type: nearby.takesFrame(view) ? 'identify' : 'frame', id: ++frameId, frame, frameRate, timeMs },
                     [frame]);
}

async function startCamera() {
  setState('camera', 'Starting the camera…');
  if (!navigator.mediaDevices?.getUserMedia) {
    startPhotoMode(window.isSecureContext ? 'no-camera' : 'insecure-context');
    return;
  }
  try {
    stream = await openCamera();
  } catch (e) {
    showError(e.code, e.message);
    $('photo').hidden = false;
    return;
  }
  const video = $('camera');
  video.srcObject = stream;
  await video.play().catch(() => {});
  setState('searching', aimingStatus());
  pumpFrames(stream, video, framesWanted, handFrame);
}

function onResult(r) {
  busy = false;
  debug.frames += 1;
  debug.lastResult = r;
  debug.detectMs = r.ms;
  if (paused()) return;
  const locked = r.state === 'locked' && !!r.point;
  drive({ event: 'frame', locked, point: locked ? r.point : undefined, confidence: r.confidence,
          another_field: r.anotherField });
}

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
    showResult({ kind: 'none', title: 'That picture could not be read', detail: e.message }, debug);
  }
}

// A photo's one result: locked at its point, then a tap there at once.
function onStill(r) {
  const point = r && r.found ? r.point || r.rawPoint : null;
  if (!point) {
    showResult({ kind: 'none', title: 'No screen found in the photo',
                 detail: 'Take it closer and straight on, with the whole crosshair area on the screen.' }, debug);
    return;
  }
  drive({ event: 'frame', locked: true, point, confidence: r.confidence });
  drive({ event: 'tap' });
}

// ---- grab ---------------------------------------------------------------------

async function receive(content) {
  setState('grabbing', `Receiving ${content.name}…`);
  try {
    const started = performance.now();
    let resumedAt = null;
    grabbed = await download(content, pairing.token, (part) => {
      // The rate over the whole transfer so far, pauses included.
      const seconds = (performance.now() - started) / 1000;
      const rate = seconds > 0.5 ? `, ${formatSize(part * content.size / seconds)}/s` : '';
      const resumed = resumedAt === null ? '' : ` (resumed at ${resumedAt})`;
      $('status').textContent = `Receiving ${content.name}… ${Math.floor(100 * part)} %${rate}${resumed}`;
    }, (received, total, why) => {
      resumedAt = formatSize(received);
      (debug.downloadResumes ??= []).push({ received, why });
      $('status').textContent =
        `Connection lost at ${formatSize(received)} of ${formatSize(total)}, resuming…`;
    });
    drive({ event: 'downloaded', ok: true });
  } catch (e) {
    grabbed = null;
    drive({ event: 'downloaded', ok: false, message: e.message });
  }
}

// ---- put ------------------------------------------------------------------------

function setMode(m) {
  mode = m;
  document.body.dataset.mode = m;
  $('grab').textContent = m === 'put' ? 'Put' : 'Grab';
  $('put-bar').hidden = m !== 'put';
  if (m === 'put') $('target-title').textContent = '';
  if (m === 'put' && putItem) $('put-bar-what').textContent = describeItem(putItem);
  drive({ event: 'auto', on: m === 'put' ? options.autoput : options.autograb });
}

// The core's Put mode with the page's item; false when the core will not
// take it (a link that is not http or https), and then nothing changed.
function choosePut(item) {
  if (!pointer) return true;  // connectToProvider chooses it once there is a core
  const chosen = { kind: item.kind, url: item.url, title: item.title, name: item.name, mime: item.mime, size: item.size };
  if (!drive({ event: 'choose_put', item: chosen })) return false;
  // A file is hashed while the user aims; the core sends the put once it has the hash.
  item.sha256?.then((sha256) => putItem === item && drive({ event: 'hashed', sha256 }),
                    (e) => putItem === item && showPutFailure('unreadable', e.message, { item, debug }));
  return true;
}

// Put mode with `item`: aim as for a grab, then Put. False when the core
// will not take the item.
function enterPut(item) {
  const previous = putItem;
  putItem = item;
  if (!choosePut(item)) {
    putItem = previous;
    return false;
  }
  cancelUpload();
  debug.put = { kind: item.kind, name: item.name, size: item.size, url: item.url, status: 'aiming' };
  hideSheets();
  hint(null);
  setMode('put');
  if (link && workerReady) backToAiming();  // else start() brings the camera up, in Put mode
  return true;
}

function leavePut() {
  cancelUpload();
  putItem = null;
  debug.put = null;
  hideSheets();
  setMode('grab');
  drive({ event: 'leave_put' });
  if (!link) start();
  else backToAiming();
}

function showPutProgress(v) {
  const item = putItem;
  if (v.put === 'hashing') showPutStatus('hashing', 'Checking the file…', describeItem(item), { debug });
  else if (v.put === 'sending')
    showPutStatus('sending', 'Giving it to the screen…', item?.kind === 'url' ? item.url : item?.name, { debug });
  else if (v.put === 'asking') askingTimer = showAskingCountdown(item, () => v.put_deadline - seconds(), debug);
}

function stopAskingCountdown() {
  clearInterval(askingTimer);
  askingTimer = null;
}

function sendPutFile(path) {
  const item = putItem;
  if (item?.kind !== 'file') return;
  putXhr = upload(path, item, (status, body) => {
    if (putXhr === null || putItem !== item) return;
    putXhr = null;
    drive(status === 0 ? { event: 'uploaded', status: 0, failure: 'the connection broke' }
      : { event: 'uploaded', status, body });
  }, debug);
}

function cancelUpload() {
  const xhr = putXhr;
  putXhr = null;
  xhr?.abort();
}

// ?share=ID: the service worker (sw.js) took a share and carried it.
async function openShare(id) {
  params.delete('share');
  history.replaceState(null, '', location.pathname + (params.toString() ? `?${params}` : '') + location.hash);
  const item = await sharedItem(id, debug);
  if (item) enterPut(item);
  return item !== null;
}

// ---- start -------------------------------------------------------------------------

async function start() {
  hideSheets();
  hint(null);
  pairing = await currentPairing();
  $('pairing-origin').textContent = location.origin;
  $('pairing-fingerprint').textContent = forPeople(pairing?.fingerprint) || '—';
  if (!pairing) {
    showError('unpaired');
    setState('unpaired', 'Not paired');
    return;
  }
  if (await moveToName(pairing, location, trust, debug)) return;
  if (!(await connectToProvider())) return;
  if (!(await startWorker())) return;
  if (stream) {
    setState('searching', aimingStatus());
    return;
  }
  if (options.photo || !window.isSecureContext) startPhotoMode(window.isSecureContext ? null : 'insecure-context');
  else await startCamera();
}

function wire() {
  const act = () => drive({ event: 'tap' });
  $('grab').addEventListener('click', act);
  $('camera').addEventListener('click', () => document.body.dataset.state === 'locked' && act());
  $('result-close').addEventListener('click', () => {
    hideSheets();
    if (!link) {
      start();
      return;
    }
    drive({ event: 'dismiss' });
    // A result of the page's own (a photo without the field) had no core result to dismiss.
    if (document.body.dataset.state === 'result') backToAiming();
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
    clearHistory();
    showHistory();
  });
  $('show-pairing').addEventListener('click', () => ($('pairing').hidden = false));
  $('show-put').addEventListener('click', () => showPutChooser(enterPut, debug));
  for (const id of ['put-close', 'put-cancel', 'put-finish']) $(id).addEventListener('click', leavePut);
  $('put-again').addEventListener('click', () => (putItem ? enterPut(putItem) : leavePut()));
  $('put-abort').addEventListener('click', () => enterPut(putItem));
  wirePutChoices(enterPut);
  $('pairing-close').addEventListener('click', () => ($('pairing').hidden = true));
  wireTrust(() => pairing?.fingerprint ?? null, debug);
  $('pairing-forget').addEventListener('click', () => {
    forget(location.origin);
    pairing = null;
    pointer?.destroy();
    pointer = null;
    link?.close();
    link = null;
    stream?.getTracks().forEach((t) => t.stop());
    stream = null;
    hideSheets();
    showError('unpaired');
    setState('unpaired', 'Not paired');
  });
  // The core's timeouts (a grab or put the screen never answers).
  setInterval(() => view && !aiming(view.phase) && drive({ event: 'tick' }), TICK_MS);
}

wire();
setMode('grab');
trust = registerServiceWorker(debug);
{
  const share = params.get('share');
  start().then(() => share && link && openShare(share));
}
