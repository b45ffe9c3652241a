// The CTest fixture web.browser.npm_install: playwright-core, pinned by
// package.json and package-lock.json beside this file, installed with `npm ci`
// into DEST (the build folder, never the source tree). Does nothing when DEST
// already holds the same lock file and its node_modules.
//
//   node npm_install.mjs --src SRC_DIR --dest DEST_DIR [--npm NPM]
//
// Exit codes: 0 installed or already there; 77 (CTest's skip) when npm is
// missing or the registry cannot be reached; 1 anything else.
import { spawnSync } from 'node:child_process';
import fs from 'node:fs';
import path from 'node:path';

const SKIP = 77;
const args = Object.fromEntries(
  process.argv.slice(2).reduce((pairs, a, i, all) => (a.startsWith('--') ? [...pairs, [a.slice(2), all[i + 1]]] : pairs), []));
if (!args.src || !args.dest) {
  console.error('usage: node npm_install.mjs --src SRC_DIR --dest DEST_DIR [--npm NPM]');
  process.exit(2);
}
const npm = args.npm && args.npm !== 'UMF_NPM-NOTFOUND' ? args.npm : 'npm';
const files = ['package.json', 'package-lock.json'];
fs.mkdirSync(args.dest, { recursive: true });

const same = (f) => {
  try { return fs.readFileSync(path.join(args.src, f)).equals(fs.readFileSync(path.join(args.dest, f))); } catch { return false; }
};
const installed = path.join(args.dest, 'node_modules', 'playwright-core', 'package.json');
if (files.every(same) && fs.existsSync(installed)) {
  const version = JSON.parse(fs.readFileSync(installed, 'utf8')).version;
  console.log(`npm_install: playwright-core ${version} already in ${args.dest}`);
  process.exit(0);
}
for (const f of files) fs.copyFileSync(path.join(args.src, f), path.join(args.dest, f));

const t0 = Date.now();
const r = spawnSync(npm, ['ci', '--no-audit', '--no-fund', '--prefix', args.dest],
  { cwd: args.dest, encoding: 'utf8', timeout: 150000 });
process.stdout.write(r.stdout || '');
process.stderr.write(r.stderr || '');
if (r.error && r.error.code === 'ENOENT') {
  console.log(`SKIP: npm (${npm}) is not installed; scripts/install-deps.sh installs it`);
  process.exit(SKIP);
}
if (r.status !== 0) {
  // Remove the copied lock so the next run tries again.
  fs.rmSync(path.join(args.dest, 'package-lock.json'), { force: true });
  if (/E(NOTFOUND|AI_AGAIN|CONNREFUSED|CONNRESET|TIMEDOUT|NETUNREACH)|network/i.test(`${r.stderr}${r.stdout}`) || r.signal) {
    console.log('SKIP: the npm registry cannot be reached, so playwright-core cannot be installed; ' +
                'the browser tests skip (run again when online)');
    process.exit(SKIP);
  }
  console.error(`npm_install: npm ci failed (exit ${r.status})`);
  process.exit(1);
}
const version = JSON.parse(fs.readFileSync(installed, 'utf8')).version;
console.log(`npm_install: playwright-core ${version} installed into ${args.dest} in ${Date.now() - t0} ms`);
