// A grab's result: the file's bytes fetched and checked, then the result
// sheet (a link to open, a file to save or open, or why nothing came), the
// history and the carry list.
import { carry } from './carry.js';
import { remember } from './history.js';
import { $, describeKind, formatSize, hideSheets, setState } from './sheets.js';
import { ResumePacing } from './resume_pacing.js';
import { Sha256 } from './sha256.js';

let objectUrl = null;

// Up to this size the whole file is hashed at the end by crypto.subtle
// (fast, native, but it takes the file as one buffer); above it, and on
// pages without crypto.subtle, the page's own SHA-256 hashes the bytes as
// they come, so memory does not grow with the file.
const WHOLE_DIGEST_MAX = 128 * 1024 * 1024;
// The bytes received are handed to a Blob in steps of this size, so the
// page does not hold them as its own buffers: the browser decides where a
// large Blob lives (Chromium pages it to disk).
const BLOB_STEP = 32 * 1024 * 1024;

// The provider's reason from its error envelope (docs/PROTOCOL.md, "Errors over HTTP").
async function refusal(response) {
  const answer = await response.json().catch(() => null);
  const error = answer?.messages?.length === 1 && answer.messages[0]?.type === 'error' ? answer.messages[0] : null;
  return error?.message || `the download answered ${response.status}`;
}

// The file of a grab's content: {blob, verified}, asked for with the
// pairing token the session proved (the link is bound to it). A connection
// that breaks is asked again for the rest (Range from the bytes held,
// If-Range with the ETag); onResume(received, total, why) hears of each
// time. Throws with a reason for people.
export async function download(content, token, onProgress, onResume) {
  const total = content.size;
  let parts = [];    // Blobs of BLOB_STEP bytes
  let chunks = [];   // the bytes since the last of them
  let pending = 0;
  let received = 0;
  let etag = '';
  const newHash = () => (content.sha256 && (!crypto.subtle || total > WHOLE_DIGEST_MAX) ? new Sha256() : null);
  let ownHash = newHash();

  // One request, for the whole file or the rest of it: null when the file
  // is complete, else why the connection broke; throws when the answer ends it.
  async function attempt() {
    const headers = token ? { Authorization: `Bearer ${token}` } : {};
    if (received > 0) {
      headers.Range = `bytes=${received}-`;
      if (etag) headers['If-Range'] = etag;
    }
    let response;
    try {
      response = await fetch(content.download, { cache: 'no-store', headers });
    } catch {
      return 'the connection failed';
    }
    if (response.status === 206) {
      const range = response.headers.get('Content-Range');
      if (received === 0 || range !== `bytes ${received}-${total - 1}/${total}`)
        throw new Error(`the screen resumed the download at another place (${range}) than the ${received} bytes held`);
    } else if (response.ok) {
      if (received > 0) {  // the whole file again
        parts = [];
        chunks = [];
        pending = 0;
        received = 0;
        ownHash = newHash();
      }
      etag = response.headers.get('ETag') || '';
    } else {
      const why = await refusal(response);
      if (response.status === 404 && received > 0)
        throw new Error(`the transfer was cut after ${received} of ${total} bytes and its link was gone when the ` +
                        `rest was asked for (${why}); nothing was kept`);
      throw new Error(why);
    }
    const reader = response.body.getReader();
    for (;;) {
      let part;
      try {
        part = await reader.read();
      } catch {
        return 'the connection was lost';
      }
      const { value, done } = part;
      if (done) break;
      chunks.push(value);
      ownHash?.update(value);
      received += value.length;
      pending += value.length;
      if (pending >= BLOB_STEP) {
        parts.push(new Blob(chunks));
        chunks = [];
        pending = 0;
      }
      if (total > 0) onProgress?.(received / total);
    }
    return received === total ? null : 'the transfer ended early';
  }

  const pacing = new ResumePacing();
  for (;;) {
    const why = await attempt();
    if (why === null) break;
    pacing.reached(received);
    if (pacing.givenUp())
      throw new Error(`the transfer was cut after ${received} of ${total} bytes (${why}) and brought nothing more ` +
                      'for 30 s of asking again, so its SHA-256 could not be checked and nothing was kept');
    onResume?.(received, total, why);
    await pacing.wait();
  }
  const blob = new Blob([...parts, ...chunks], { type: content.mime });
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

async function keepCarried(entry, debug) {
  try {
    await carry(entry);
  } catch (e) {
    // Without IndexedDB (private browsing) the carry list stays empty.
    debug.carryError = e.message;
  }
}

export function showResult({ kind, title, url, file, bytes, detail }, debug) {
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
  if (kind === 'url') keepCarried({ kind: 'url', url, title }, debug);
  else if (file && bytes) keepCarried({ kind: 'file', title, name: file.name, mime: file.mime, blob: bytes.blob,
                                        sha256: bytes.verified ? file.sha256 : undefined }, debug);
  hideSheets();
  sheet.hidden = false;
  setState('result', kind === 'none' ? 'Nothing taken' : 'Taken');
}

// The core's outcome of a grab (pointer.js, view.outcome) on the result
// sheet; `bytes` are the file's when its download was the one that ended it.
export function showGrabOutcome(outcome, bytes, debug) {
  const content = outcome.content;
  if (outcome.ok && content.kind === 'url') {
    showResult({ kind: 'url', title: content.title || content.url, url: content.url }, debug);
  } else if (outcome.ok && (content.kind === 'file' || content.kind === 'snapshot')) {
    showResult({ kind: content.kind, title: content.title || content.name, file: content, bytes }, debug);
  } else if (outcome.ok) {
    showResult({ kind: 'none', title: content.title || 'Nothing to take here' }, debug);
  } else if (outcome.code === 'download') {
    showResult({ kind: 'none', title: 'The transfer failed', detail: outcome.message }, debug);
  } else {
    showResult({ kind: 'none', title: outcome.code === 'not_found' ? 'No screen there' : 'Not taken',
                 detail: outcome.message }, debug);
  }
}
