// The requester core's scenarios (tests/data/requester_core/*.json) on the
// phone page's copy of the core: the WebAssembly module through pointer.js,
// as the page loads it. The native build runs the same files
// (tests/requester_core/pointer_scenarios_test.cpp), with the same matching:
// every key an "expect" has must match (null: absent or null), arrays element
// by element and of the same length, numbers to 1e-9; a "refused" step's
// event must be refused.
//
//   node --no-experimental-fetch tests/web/requester_core_scenarios.mjs SCENARIO_DIR SITE_DIR
import fs from 'fs';
import path from 'path';
import { pathToFileURL } from 'url';

const [scenarioDir, siteDir] = process.argv.slice(2);
if (!scenarioDir || !siteDir) {
  console.error('usage: requester_core_scenarios.mjs SCENARIO_DIR SITE_DIR');
  process.exit(2);
}
const { createPointer, parsePairingUrl } = await import(pathToFileURL(path.join(siteDir, 'pointer.js')).href);

function difference(expected, actual, at) {
  if (expected === null) return actual === null || actual === undefined ? '' : `${at}: expected null, got ${JSON.stringify(actual)}`;
  if (Array.isArray(expected)) {
    if (!Array.isArray(actual) || actual.length !== expected.length)
      return `${at}: expected ${JSON.stringify(expected)}, got ${JSON.stringify(actual)}`;
    for (let i = 0; i < expected.length; ++i) {
      const d = difference(expected[i], actual[i], `${at}[${i}]`);
      if (d) return d;
    }
    return '';
  }
  if (typeof expected === 'object') {
    if (typeof actual !== 'object' || actual === null || Array.isArray(actual))
      return `${at}: expected an object, got ${JSON.stringify(actual)}`;
    for (const [key, value] of Object.entries(expected)) {
      if (!(key in actual)) {
        if (value === null) continue;
        return `${at}.${key}: missing`;
      }
      const d = difference(value, actual[key], `${at}.${key}`);
      if (d) return d;
    }
    return '';
  }
  if (typeof expected === 'number' && typeof actual === 'number')
    return Math.abs(expected - actual) <= 1e-9 ? '' : `${at}: expected ${expected}, got ${actual}`;
  return expected === actual ? '' : `${at}: expected ${JSON.stringify(expected)}, got ${JSON.stringify(actual)}`;
}

// The matcher itself must see differences, or every scenario would pass.
if (!difference({ send: [{ type: 'aim' }] }, { send: [] }, 'a') || !difference({ x: null }, { x: 1 }, 'a')
    || difference({ x: null }, {}, 'a')) {
  console.error('the matcher is broken');
  process.exit(1);
}

const welcome = JSON.parse(fs.readFileSync(path.join(scenarioDir, 'welcome.json'), 'utf8'));
const names = fs.readdirSync(scenarioDir).filter((n) => n.endsWith('.json') && n !== 'welcome.json').sort();
let failures = 0, steps = 0;
for (const name of names) {
  const scenario = JSON.parse(fs.readFileSync(path.join(scenarioDir, name), 'utf8'));
  const setup = { welcome };
  for (const key of ['auto', 'timing']) if (key in scenario) setup[key] = scenario[key];
  const pointer = await createPointer(setup);
  scenario.steps.forEach((step, index) => {
    ++steps;
    let answer = null, refused = null;
    try {
      answer = pointer.event(step.event);
    } catch (e) {
      refused = e;
    }
    let problem = '';
    if (step.refused) problem = refused ? '' : 'the event was not refused';
    else if (refused) problem = `refused: ${refused.message}`;
    else if (step.expect) problem = difference(step.expect, answer, 'answer');
    if (problem) {
      ++failures;
      console.error(`${name}, step ${index} ${JSON.stringify(step.event)}: ${problem}`);
    }
  });
  pointer.destroy();
}
// The page reads its pairing URL with the protocol's codec too (pairing.js).
const fp = 'ab'.repeat(32);
const paired = await parsePairingUrl(`https://desk.local:8443/#t=3q2-7wEe9KcFzE1p0xH4aA&fp=${fp.toUpperCase()}`);
if (paired.token !== '3q2-7wEe9KcFzE1p0xH4aA' || paired.fingerprint !== fp || paired.port !== 8443) {
  ++failures;
  console.error(`the pairing URL was read as ${JSON.stringify(paired)}`);
}
for (const bad of [`https://desk.local:8443/#t=short&fp=${fp}`, `https://desk.local:8443/#t=3q2-7wEe9KcFzE1p0xH4aA`,
                   `http://desk.local:8443/#t=3q2-7wEe9KcFzE1p0xH4aA&fp=${fp}`]) {
  const refused = await parsePairingUrl(bad).then(() => false, () => true);
  if (!refused) {
    ++failures;
    console.error(`the pairing URL ${bad} was not refused`);
  }
}
console.log(`${names.length} scenarios, ${steps} steps, pairing URLs, ${failures} failed`);
process.exit(failures ? 1 : 0);
