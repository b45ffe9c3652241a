// The page's own SHA-256 (web/site/sha256.js, for pages without
// crypto.subtle) against node's, fed in uneven pieces across block edges.
//   node tests/web/sha256_test.mjs web/site/sha256.js
import crypto from 'node:crypto';
import path from 'node:path';
import { pathToFileURL } from 'node:url';

const { Sha256 } = await import(pathToFileURL(path.resolve(process.argv[2])).href);
let failures = 0;
for (const n of [0, 1, 3, 55, 56, 63, 64, 65, 119, 120, 1000, 100000, 1 << 20]) {
  const bytes = crypto.randomBytes(n);
  const ours = new Sha256();
  for (let i = 0; i < n;) {
    const k = Math.min(n - i, 1 + ((i * 7) % 97));
    ours.update(bytes.subarray(i, i + k));
    i += k;
  }
  const want = crypto.createHash('sha256').update(bytes).digest('hex');
  const got = ours.hex();
  if (got !== want) {
    console.log(`${n} bytes: ${got}, want ${want}`);
    ++failures;
  }
}
if (new Sha256().update(new TextEncoder().encode('abc')).hex() !==
    'ba7816bf8f01cfea414140de5dae2223b00361a396177a9cb410ff61f20015ad') {
  console.log('"abc" does not give the FIPS 180-4 example digest');
  ++failures;
}
console.log(failures ? `sha256: ${failures} failures` : 'sha256: ok');
process.exit(failures ? 1 : 0);
