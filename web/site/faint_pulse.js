// Whether the screen's field pulses too faintly for the tracker to lock on
// in one frame (the invisible preset's 0.01..0.04; it locks on 0.1 and
// above): the worker then also searches the frames together
// (detector.js, setPulse).
export const kFaintOpacity = 0.1;

// The welcome's overlay -> {waveform, periodS, range} for setPulse, or null
// for a field strong enough or static.
export function faintPulse(overlay) {
  if (!(overlay?.period_s > 0) || !(overlay.opacity_max < kFaintOpacity)) return null;
  const range = { min: overlay.opacity_min ?? 0, max: overlay.opacity_max };
  return { waveform: overlay.waveform, periodS: overlay.period_s, range };
}
