// The requester core for the page: shared/requester_core's Pointer in the
// same WebAssembly module as the detector (web/wasm/pointer_module.cpp).
//
//   import { createPointer } from './pointer.js';
//   const pointer = await createPointer({ welcome, auto: false });
//   const answer = pointer.event({ event: 'frame', t: performance.now() / 1000, locked, point, confidence });
//   for (const m of answer.send) link.send(m);   // then answer.download, answer.upload, answer.reconnect
//   show(answer.view);
//   pointer.destroy();
//
// An event the core cannot read throws, naming what is wrong. The pairing
// URL is read by the same codec as the provider's and umf-requester's:
//   const { token, fingerprint } = await parsePairingUrl('https://host:port/#t=...&fp=...');
import { cString, loadModule, withText } from './umf_module.js';

// setup: {welcome, auto?, timing?} (requester_core/pointer_json.hpp).
export async function createPointer(setup, { moduleOptions } = {}) {
  const M = await loadModule(moduleOptions);
  let handle = withText(M, JSON.stringify(setup), (ptr, n) => M._umf_pointer_create(ptr, n));
  if (!handle) throw new Error(`umf pointer: ${cString(M, M._umf_pointer_error()) || 'cannot start'}`);
  return {
    event(e) {
      if (!handle) throw new Error('umf pointer: used after destroy()');
      const answer = JSON.parse(cString(M, withText(M, JSON.stringify(e), (ptr, n) => M._umf_pointer_event(handle, ptr, n))));
      if (answer.error) throw new Error(`umf pointer: ${answer.error}`);
      return answer;
    },
    destroy() {
      if (handle) M._umf_pointer_destroy(handle);
      handle = 0;
    },
  };
}

// {host, port, token, fingerprint} of a pairing URL; throws with what is wrong.
export async function parsePairingUrl(url, { moduleOptions } = {}) {
  const M = await loadModule(moduleOptions);
  const answer = JSON.parse(cString(M, withText(M, String(url), (ptr, n) => M._umf_parse_pairing_url(ptr, n))));
  if (answer.error) throw new Error(answer.error);
  return answer;
}
