// Put mode's sheets: the chooser (a file, a photo, a link, a note, the carry
// list), the status of a put under way, and the upload's bytes. Whether and
// when a put goes, and what its answers mean, is the requester core's
// (pointer.js); this shows it and moves the bytes it asks for.
import { getCarried, listCarried, noteFile, removeCarried } from './carry.js';
import { ResumePacing } from './resume_pacing.js';
import { $, PUT_ERRORS, formatSize, hideSheets, setState } from './sheets.js';
import { Sha256 } from './sha256.js';

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

// A file to put: hashed while the user aims (item.sha256, a promise).
export function fileItem(blob, { name, title, mime, sha256, carriedId } = {}) {
  const item = { kind: 'file', blob, name: name ?? blob.name ?? '', mime: mime ?? blob.type ?? '',
                 size: blob.size, title: title || name || blob.name || '', carriedId };
  item.sha256 = sha256 ? Promise.resolve(sha256) : sha256Hex(blob);
  item.sha256.catch(() => {});
  return item;
}

export function carriedItem(e) {
  return e.kind === 'url' ? { kind: 'url', url: e.url, title: e.title, carriedId: e.id }
    : fileItem(e.blob, { name: e.name, title: e.title, mime: e.mime, sha256: e.sha256, carriedId: e.id });
}

// What the put bar and the status sheet call the item.
export function describeItem(item) {
  return item?.kind === 'url' ? item.url : `${item?.name} · ${formatSize(item?.size ?? 0)}`;
}

// The chooser's own ways to choose: a file, a photo, a link, a note. `choose`
// (the page's enterPut) is false when the core will not take the item.
export function wirePutChoices(choose) {
  for (const id of ['put-file', 'put-photo']) {
    $(id).addEventListener('change', (e) => {
      const file = e.target.files?.[0];
      e.target.value = '';  // choosing the same file again is a new choice
      if (file) choose(fileItem(file, { name: file.name || (id === 'put-photo' ? `photo-${Date.now()}.jpg` : 'file') }));
    });
  }
  $('put-url-form').addEventListener('submit', (e) => {
    e.preventDefault();
    // The core judges the link; one it will not take stays on the chooser.
    if (!choose({ kind: 'url', url: $('put-url').value.trim(), title: '' })) $('put-url-error').hidden = false;
  });
  $('put-note-form').addEventListener('submit', (e) => {
    e.preventDefault();
    const text = $('put-note').value;
    if (!text.trim()) return;
    const note = noteFile(text);
    choose(fileItem(note.blob, { name: note.name, title: 'Note', mime: 'text/plain' }));
  });
}

// ?share=ID: what the service worker (sw.js) carried for it, or null after
// saying why there is nothing.
export async function sharedItem(id, debug) {
  debug.share = { id };
  if (!/^\d+$/.test(id)) {
    const code = { unavailable: 'share-unavailable', empty: 'share-empty', 'too-large': 'share-too-large' }[id] || 'share-missing';
    showPutFailure(code, undefined, { debug });
    return null;
  }
  let e = null;
  try {
    e = await getCarried(id);
  } catch (err) {
    debug.carryError = err.message;
  }
  if (!e) {
    showPutFailure('share-missing', undefined, { debug });
    return null;
  }
  debug.share.kind = e.kind;
  return carriedItem(e);
}

export async function showPutChooser(onChoose, debug) {
  hideSheets();
  $('put-url-error').hidden = true;
  $('put').hidden = false;
  setState('put-choose', 'Choose what to put on the screen');
  await showCarried(onChoose, debug);
}

async function showCarried(onChoose, debug) {
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
    put.addEventListener('click', () => onChoose(carriedItem(e)));
    const remove = document.createElement('button');
    remove.type = 'button';
    remove.className = 'carry-remove';
    remove.textContent = 'Remove';
    remove.setAttribute('aria-label', `Remove ${e.kind === 'url' ? e.url : e.name}`);
    remove.addEventListener('click', async () => {
      await removeCarried(e.id).catch(() => {});
      showCarried(onChoose, debug);
    });
    li.append(put, remove);
    return li;
  }));
  $('carry-empty').hidden = items.length > 0;
}

// `canAgain`: a put item is there to try once more.
export function showPutStatus(status, title, text, { code, progress, outcome, name, canAgain, debug } = {}) {
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
  $('put-again').hidden = !over || status === 'done' || !canAgain;
  $('put-finish').hidden = !over;
  $('put-abort').hidden = over;
  if (debug?.put) Object.assign(debug.put, { status, code: code ?? null, outcome: outcome ?? null, name: name ?? null });
  hideSheets();
  sheet.hidden = false;
  setState(over ? 'put-result' : 'putting', title);
}

export function showPutFailure(code, detail, { item, debug } = {}) {
  const [title, text] = PUT_ERRORS[code] || ['Not put', ''];
  showPutStatus('error', title, detail && !PUT_ERRORS[code] ? `${text} (${detail})` : text,
                { code, canAgain: !!item, debug });
}

// While the screen's person decides: the seconds they have left, counted
// down; `secondsLeft` reads the core's deadline. Returns the interval to clear.
export function showAskingCountdown(item, secondsLeft, debug) {
  const what = item?.kind === 'url' ? item.url : `${item?.name} (${describeItem(item).split(' · ')[1]})`;
  showPutStatus('asking', 'Waiting for the screen to accept…', '', { debug });
  const tick = () => {
    const left = Math.max(0, Math.ceil(secondsLeft()));
    $('put-status-text').textContent = `${what} — someone at the screen has ${left} s to accept it.`;
  };
  tick();
  return setInterval(tick, 1000);
}

export function showPutDone(status, item, debug) {
  const what = item?.kind === 'url' ? 'The link' : item?.name || 'It';
  if (status.outcome === 'opened')
    showPutStatus('done', 'Opened on the screen', status.name ? `${status.name} was saved and opened.` : `${what} is open on the screen.`,
                  { outcome: 'opened', name: status.name, debug });
  else
    showPutStatus('done', 'Saved on the screen', `Saved as ${status.name}.`, { outcome: 'saved', name: status.name, debug });
}

// How many bytes the screen holds (HEAD): a number, 'gone' for an ended
// link, or null when it cannot be asked now.
async function heldBytes(path) {
  try {
    const response = await fetch(path, { method: 'HEAD', cache: 'no-store' });
    if (response.status === 404) return 'gone';
    const held = Number(response.headers.get('Upload-Offset'));
    return response.ok && Number.isInteger(held) ? held : null;
  } catch {
    return null;
  }
}

// The bytes go with XMLHttpRequest, the one browser API that reports an
// upload's progress; the browser sets Content-Length from the Blob. A
// connection that breaks goes on from what the screen holds (HEAD, then
// PUT with Upload-Offset). `answered` gets the HTTP status (0: the
// connection broke and could not go on) and the body. Returns what stops it
// (abort()).
export function upload(path, item, answered, debug) {
  let xhr = null;
  let stopped = false;
  const pacing = new ResumePacing();
  showPutStatus('upload', `Sending ${item.name}…`, `0 of ${formatSize(item.size)}`, { progress: 0, debug });

  const send = (from) => {
    xhr = new XMLHttpRequest();
    xhr.upload.onprogress = (e) => {
      const sent = from + e.loaded;
      $('put-progress').value = item.size > 0 ? sent / item.size : 1;
      $('put-status-text').textContent = `${formatSize(sent)} of ${formatSize(item.size)}` +
        (from > 0 ? ` (resumed at ${formatSize(from)})` : '');
    };
    xhr.onload = () => (xhr.status === 409 ? resume() : answered(xhr.status, xhr.responseText));
    xhr.onerror = () => resume();
    xhr.open('PUT', path);
    xhr.setRequestHeader('Upload-Offset', String(from));
    xhr.send(from > 0 ? item.blob.slice(from) : item.blob);
  };

  const resume = async () => {
    for (;;) {
      if (stopped) return;
      await pacing.wait();
      if (stopped) return;
      const held = await heldBytes(path);
      if (held === 'gone') {
        answered(404, '');
        return;
      }
      if (held !== null) pacing.reached(held);
      if (pacing.givenUp()) {
        answered(0, '');
        return;
      }
      if (held === null) continue;
      (debug.putResumes ??= []).push(held);
      $('put-status-text').textContent =
        `Connection lost at ${formatSize(held)} of ${formatSize(item.size)}, resuming…`;
      send(held);
      return;
    }
  };

  send(0);
  return { abort() { stopped = true; xhr?.abort(); } };
}
