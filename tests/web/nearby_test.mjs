// The page's choice among the screens nearby (web/site/nearby.js), with the
// network and the detector's worker played by this script: only screens
// whose field could be fetched are tried, exactly one found is offered,
// two at once (a field claimed twice) or two misses in a row offer nothing,
// and a list that is not the screen's own form is left out.
//   node tests/web/nearby_test.mjs web/site/nearby.js
import path from 'node:path';
import { pathToFileURL } from 'node:url';

const { createNearby } = await import(pathToFileURL(path.resolve(process.argv[2])).href);
let failures = 0;
const check = (ok, what) => {
  if (!ok) {
    console.log(`FAIL: ${what}`);
    ++failures;
  }
};

globalThis.location = { origin: 'https://a.local:8443' };
const served = {
  '/nearby.json': { screens: [
    { name: 'umf on b', origin: 'https://b.local:9443', fingerprint: 'b'.repeat(64) },
    { name: 'umf on c', origin: 'https://c.local:9443', fingerprint: 'c'.repeat(64) },
    { name: 'umf on untrusted', origin: 'https://u.local:9443', fingerprint: 'd'.repeat(64) },
    { name: 'umf on itself', origin: 'https://a.local:8443', fingerprint: 'a'.repeat(64) },
    { name: 'a page elsewhere', origin: 'https://evil.example:443', fingerprint: 'e'.repeat(64) },
    { name: 'not https', origin: 'http://h.local:80', fingerprint: 'f'.repeat(64) },
    { name: 'a path', origin: 'https://p.local:9443/x', fingerprint: '1'.repeat(64) },
  ] },
  'https://b.local:9443/field.json': { id: 'b' },
  'https://c.local:9443/field.json': { id: 'c' },
};
const asked = [];
globalThis.fetch = async (url) => {
  asked.push(url);
  if (!(url in served)) throw new TypeError('Failed to fetch');  // what an untrusted certificate gives
  return { ok: true, status: 200, json: async () => served[url] };
};
const posted = [];
const worker = { postMessage: (m) => posted.push(m) };
const debug = {};
const nearby = createNearby(worker, debug);
const other = { phase: 'searching', another_screen: true };

check(!nearby.takesFrame(other), 'no frame before the list');
nearby.viewed(other);
for (let i = 0; i < 50 && posted.length === 0; ++i) await new Promise((r) => setTimeout(r, 10));
check(posted.length === 1 && posted[0].type === 'nearby-fields', 'the fields go to the worker');
check(JSON.stringify(posted[0].fields) === '[{"id":"b"},{"id":"c"}]', `the fetched fields, in order (${JSON.stringify(posted[0].fields)})`);
check(!asked.some((u) => /evil|h\.local|p\.local|a\.local/.test(u)), `only .local https origins of others are asked (${asked.join(' ')})`);
check(debug.nearby.listed === 3 && debug.nearby.fetched === 2, `listed 3, fetched 2 (${JSON.stringify(debug.nearby)})`);

check(nearby.takesFrame(other), 'a frame is taken once the fields are in');
check(!nearby.takesFrame(other), 'one frame at a time');
nearby.identified([1]);
check(nearby.match()?.name === 'umf on c', 'one field found: its screen is offered');
nearby.identified([]);
check(nearby.match()?.name === 'umf on c', 'one miss keeps the offer');
nearby.identified([]);
check(nearby.match() === null, 'a second miss in a row withdraws it');
nearby.identified([0]);
check(nearby.match()?.name === 'umf on b', 'found again');
nearby.identified([0, 1]);
check(nearby.match() === null, 'two fields in one frame: nothing is offered');
nearby.identified([0]);
nearby.viewed({ phase: 'searching', another_screen: false });
check(nearby.match() === null, 'the own screen again: the offer goes');
check(!nearby.takesFrame({ phase: 'searching' }), 'no frames for the others while the own screen is seen');

// A screen without the list (an older provider): nothing offered, nothing thrown.
delete served['/nearby.json'];
const quiet = createNearby({ postMessage: () => {} }, {});
quiet.viewed(other);
await new Promise((r) => setTimeout(r, 50));
check(!quiet.takesFrame(other) && quiet.match() === null, 'no list: no frames wanted, no offer');

console.log(failures ? `nearby: ${failures} failures` : 'nearby: ok');
process.exit(failures ? 1 : 0);
