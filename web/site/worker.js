// The detector's thread: frames from the camera (VideoFrame, or ImageBitmap
// where the browser has no MediaStreamTrackProcessor) or one photo, turned
// into RGBA and given to the same Tracker the native requester runs
// (detector.js over umf-detector.wasm). One frame at a time: the page sends
// the next only after this one's result, so nothing queues up. While the
// camera sees another screen, a frame now and then goes to the fields of the
// screens nearby instead (nearby.js), each searched from scratch.
import { createDetector } from './detector.js';

let detector = null;
let frameRate = 0;  // the camera's, as the detector was last told (0: every search on every frame)
let pulse = null;  // the screen's faint pulse, {waveform, periodS}, searched over frames; null: none
let nearby = [];  // one detector per nearby screen's field, in the page's order
let canvas = null;
let context = null;
let rgba = null;
let copyToRgba = typeof VideoFrame !== 'undefined';  // until a copyTo with a format conversion fails

// A frame's RGBA pixels, at most maxSide on its longer side (photos).
async function pixelsOf(source, maxSide = Infinity) {
  const width0 = source.displayWidth ?? source.width;
  const height0 = source.displayHeight ?? source.height;
  const scale = Math.min(1, maxSide / Math.max(width0, height0));
  const width = Math.round(width0 * scale), height = Math.round(height0 * scale);
  if (copyToRgba && scale === 1 && typeof VideoFrame !== 'undefined' && source instanceof VideoFrame) {
    try {
      const bytes = width * height * 4;
      if (!rgba || rgba.length !== bytes) rgba = new Uint8Array(bytes);
      await source.copyTo(rgba, { format: 'RGBA', colorSpace: 'srgb' });
      return { data: rgba, width, height };
    } catch {
      copyToRgba = false;  // an older browser: draw it instead
    }
  }
  if (!canvas || canvas.width !== width || canvas.height !== height) {
    canvas = new OffscreenCanvas(width, height);
    context = canvas.getContext('2d', { willReadFrequently: true });
  }
  context.drawImage(source, 0, 0, width, height);
  return { data: context.getImageData(0, 0, width, height).data, width, height };
}

function track(pixels, timeMs) {
  const t0 = performance.now();
  const result = detector.track(pixels.data, pixels.width, pixels.height, { format: 'rgba', timeMs });
  return { ...result, width: pixels.width, height: pixels.height, totalMs: performance.now() - t0 };
}

self.onmessage = async (event) => {
  const message = event.data;
  try {
    if (message.type === 'field') {
      detector?.destroy();
      detector = null;
      detector = await createDetector(message.field);
      frameRate = 0;
      pulse = message.pulse ?? null;
      if (pulse) detector.setPulse(pulse.waveform, pulse.periodS, pulse.range);
      self.postMessage({ type: 'ready' });
    } else if (message.type === 'frame') {
      const frame = message.frame;
      try {
        if (!detector) throw new Error('no field yet');
        // A frame without a lock searches what fits between two of the camera's.
        const rate = message.frameRate > 0 ? message.frameRate : 0;
        if (rate !== frameRate) {
          detector.setFrameRate(rate);  // the pulse, if any, is kept
          frameRate = rate;
        }
        const pixels = await pixelsOf(frame);
        self.postMessage({ type: 'result', id: message.id, result: track(pixels, message.timeMs) });
      } finally {
        frame.close?.();
      }
    } else if (message.type === 'still') {
      // A photo: searched from scratch, at a size the detector reads well.
      const bitmap = message.bitmap;
      try {
        if (!detector) throw new Error('no field yet');
        // Every search, not a camera frame's share.
        detector.setFrameRate(0);
        frameRate = 0;
        let result = null;
        for (const side of [1920, 1280, 960]) {
          result = track(await pixelsOf(bitmap, side));
          if (result.found) break;
          detector.reset();
        }
        self.postMessage({ type: 'still-result', id: message.id, result });
      } finally {
        bitmap.close?.();
      }
    } else if (message.type === 'nearby-fields') {
      for (const d of nearby) d?.destroy();  // null: a field that could not be used
      nearby = [];
      // A field this detector cannot use is a screen not offered: the rest stay in order.
      for (const field of message.fields)
        nearby.push(await createDetector(field).catch(() => null));
    } else if (message.type === 'identify') {
      const frame = message.frame;
      try {
        const pixels = await pixelsOf(frame);
        const found = [];
        nearby.forEach((d, i) => {
          if (!d) return;
          d.reset();
          if (d.track(pixels.data, pixels.width, pixels.height, { format: 'rgba' }).found) found.push(i);
        });
        self.postMessage({ type: 'identified', id: message.id, found });
      } finally {
        frame.close?.();
      }
    } else if (message.type === 'reset') {
      detector?.reset();
    }
  } catch (e) {
    self.postMessage({ type: 'failure', id: message.id, message: String(e?.message || e) });
  }
};
