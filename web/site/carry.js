// The carry list: what this phone took from a screen (and what was shared to
// the page), kept so that it can be put on a screen with one tap. Files are
// kept as their bytes in IndexedDB, links as text. Only the newest
// CARRY_MAX_ITEMS, and of those only as many files as fit CARRY_MAX_BYTES:
// the oldest are dropped first. Used by the page (app.js) and by the service
// worker (sw.js, for shares), so nothing here touches the window.
//
// An item: {id, at, kind: 'url'|'file', title, url} or
//          {id, at, kind: 'file', title, name, mime, size, sha256?, blob}
export const CARRY_MAX_ITEMS = 20;
export const CARRY_MAX_BYTES = 200 * 1024 * 1024;

const DB_NAME = 'umf-carry';
const STORE = 'items';

let opening = null;

function openDb() {
  if (!opening) {
    opening = new Promise((resolve, reject) => {
      if (!globalThis.indexedDB) {
        reject(new Error('this browser keeps no IndexedDB here'));
        return;
      }
      const request = indexedDB.open(DB_NAME, 1);
      request.onupgradeneeded = () => request.result.createObjectStore(STORE, { keyPath: 'id', autoIncrement: true });
      request.onsuccess = () => {
        const db = request.result;
        // Another tab (or the service worker) upgrading: let it, open again later.
        db.onversionchange = () => {
          db.close();
          opening = null;
        };
        resolve(db);
      };
      request.onerror = () => reject(request.error);
    });
    opening.catch(() => { opening = null; });
  }
  return opening;
}

function finished(tx) {
  return new Promise((resolve, reject) => {
    tx.oncomplete = () => resolve();
    tx.onerror = tx.onabort = () => reject(tx.error || new Error('the carry list could not be changed'));
  });
}

function result(request) {
  return new Promise((resolve, reject) => {
    request.onsuccess = () => resolve(request.result);
    request.onerror = () => reject(request.error);
  });
}

const newestFirst = (a, b) => b.at - a.at || b.id - a.id;

// Everything carried, newest first.
export async function listCarried() {
  const db = await openDb();
  const items = await result(db.transaction(STORE, 'readonly').objectStore(STORE).getAll());
  return items.sort(newestFirst);
}

export async function getCarried(id) {
  const db = await openDb();
  return (await result(db.transaction(STORE, 'readonly').objectStore(STORE).get(Number(id)))) || null;
}

export async function removeCarried(id) {
  const db = await openDb();
  const tx = db.transaction(STORE, 'readwrite');
  tx.objectStore(STORE).delete(Number(id));
  await finished(tx);
}

// A note typed or shared on the phone, as the text file a screen saves:
// named after its first words ("Call Anna at 3.txt"), "note.txt" without any.
export function noteFile(text) {
  const first = String(text).trim().split('\n')[0]
    .replace(/[\\/:*?"<>|\x00-\x1f\x7f]+/g, ' ').replace(/\s+/g, ' ').trim().slice(0, 40).trim();
  return { name: `${first || 'note'}.txt`, blob: new Blob([String(text)], { type: 'text/plain' }) };
}

// Adds an item on top and returns its id. The same link or the same bytes
// carried before move to the top instead of being kept twice. A file larger
// than the whole allowance is not kept (null).
export async function carry(entry) {
  const item = { kind: entry.kind, title: entry.title || '', at: Date.now() };
  if (entry.kind === 'url') {
    item.url = entry.url;
  } else {
    if (!(entry.blob instanceof Blob) || entry.blob.size > CARRY_MAX_BYTES) return null;
    Object.assign(item, { name: entry.name, mime: entry.mime || entry.blob.type || 'application/octet-stream',
                          size: entry.blob.size, blob: entry.blob });
    if (entry.sha256) item.sha256 = entry.sha256;
  }
  const db = await openDb();
  const tx = db.transaction(STORE, 'readwrite');
  const store = tx.objectStore(STORE);
  const all = (await result(store.getAll())).sort(newestFirst);
  const same = (e) => e.kind === item.kind &&
    (item.kind === 'url' ? e.url === item.url
                         : e.name === item.name && e.size === item.size && (!item.sha256 || e.sha256 === item.sha256));
  const id = await result(store.add(item));
  let bytes = item.size || 0;
  let count = 1;
  for (const e of all) {
    const fits = count < CARRY_MAX_ITEMS && bytes + (e.size || 0) <= CARRY_MAX_BYTES;
    if (same(e) || !fits) {
      store.delete(e.id);
    } else {
      count += 1;
      bytes += e.size || 0;
    }
  }
  await finished(tx);
  return id;
}
