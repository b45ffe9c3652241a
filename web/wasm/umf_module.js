// The one instance of the WebAssembly module (umf-detector.js + .wasm, next
// to this file in web/site/) per thread, shared by the detector (detector.js)
// and the requester core (pointer.js), and the two ways text crosses into it.
import createUmfDetectorModule from './umf-detector.js';

let sharedModule = null;

// `moduleOptions` go to the emscripten factory on first use (for example
// `wasmBinary`, or `locateFile` when the .wasm lies elsewhere).
export function loadModule(moduleOptions) {
  // The .wasm next to umf-detector.js: emscripten's own default is a URL,
  // which its node path cannot read.
  if (!sharedModule) sharedModule = createUmfDetectorModule({ locateFile: (p, dir) => dir + p, ...moduleOptions });
  return sharedModule;
}

// The NUL-terminated UTF-8 text at `ptr` ('' for null).
export function cString(M, ptr) {
  if (!ptr) return '';
  const heap = M.HEAPU8;
  let end = ptr;
  while (heap[end] !== 0) ++end;
  return new TextDecoder().decode(heap.subarray(ptr, end));
}

// f(ptr, length) with `text` copied into the module's memory for the call.
export function withText(M, text, f) {
  const bytes = new TextEncoder().encode(text);
  const ptr = M._malloc(Math.max(1, bytes.length));
  if (!ptr) throw new Error('umf: out of memory in the WebAssembly module');
  try {
    M.HEAPU8.set(bytes, ptr);
    return f(ptr, bytes.length);
  } finally {
    M._free(ptr);
  }
}
