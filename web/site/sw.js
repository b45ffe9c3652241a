// The service worker: it exists for "Share → umf" (the manifest's
// share_target). A share arrives as a POST of multipart form data to
// /share, which only a service worker can take in (the provider answers it
// with a redirect to ?share=unavailable). What was shared goes on the carry
// list (carry.js) and the page opens with ?share=ID, in Put mode with it.
// Every other request goes to the provider as if there were no worker: the
// page is always the provider's current one.
import { carry, noteFile } from './carry.js';

const SHARE_PATH = new URL('./share', self.registration.scope).pathname;

self.addEventListener('install', () => self.skipWaiting());
self.addEventListener('activate', (event) => event.waitUntil(self.clients.claim()));

self.addEventListener('fetch', (event) => {
  const url = new URL(event.request.url);
  if (event.request.method === 'POST' && url.origin === self.location.origin && url.pathname === SHARE_PATH)
    event.respondWith(takeShare(event.request));
});

// The first link found in what was shared: Android apps put it in `url`,
// in `text`, or in `text` after a sentence.
function findUrl(...candidates) {
  for (const c of candidates) {
    const m = /\bhttps?:\/\/[^\s<>"]+/i.exec(c || '');
    if (m) return m[0];
  }
  return null;
}

async function takeShare(request) {
  const page = new URL('./', self.registration.scope);
  try {
    const form = await request.formData();
    const title = String(form.get('title') || '').slice(0, 200);
    const text = String(form.get('text') || '');
    const files = form.getAll('file').filter((f) => f instanceof File);
    const ids = [];
    // Carried newest first: the first file shared ends on top.
    for (const f of files.reverse()) {
      const id = await carry({ kind: 'file', title: title || f.name, name: f.name || 'shared file',
                               mime: f.type || 'application/octet-stream', blob: f });
      if (id !== null) ids.unshift(id);
    }
    const link = findUrl(form.get('url'), text);
    if (link && !files.length) {
      ids.unshift(await carry({ kind: 'url', url: link, title: title || text.replace(link, '').trim() }));
    } else if (!files.length && text.trim()) {
      // Plain text (a note, a paragraph) travels as a text file.
      const note = noteFile(text);
      const id = await carry({ kind: 'file', title: title || 'Note', name: note.name, mime: 'text/plain', blob: note.blob });
      if (id !== null) ids.unshift(id);
    }
    page.searchParams.set('share', ids.length ? String(ids[0]) : (files.length ? 'too-large' : 'empty'));
  } catch (e) {
    page.searchParams.set('share', 'failed');
  }
  return Response.redirect(page.href, 303);
}
