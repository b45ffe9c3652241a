// The phone's camera: opened facing the screen, its frames handed on one at
// a time (the next only when `wanted()` says so, which is after the last
// one's result) without a copy where the browser allows.

// The back camera at up to 1280 x 720 with continuous focus where offered.
// Throws {code: 'camera-denied' | 'no-camera', message}.
export async function openCamera() {
  let stream;
  try {
    stream = await navigator.mediaDevices.getUserMedia({
      audio: false,
      video: { facingMode: { ideal: 'environment' }, width: { ideal: 1280 }, height: { ideal: 720 } },
    });
  } catch (e) {
    const code = e.name === 'NotAllowedError' || e.name === 'SecurityError' ? 'camera-denied' : 'no-camera';
    throw Object.assign(new Error(e.name), { code });
  }
  const track = stream.getVideoTracks()[0];
  // Continuous focus where the camera offers it: a fixed focus blurs the screen's modules.
  try {
    if (track.getCapabilities?.().focusMode?.includes('continuous'))
      await track.applyConstraints({ advanced: [{ focusMode: 'continuous' }] });
  } catch { /* not offered */ }
  return stream;
}

// Calls hand(frame, transfer) for each frame while wanted(); the frame is a
// VideoFrame straight from the track, or a bitmap of the video element
// where the browser has no MediaStreamTrackProcessor.
export function pumpFrames(stream, video, wanted, hand) {
  const track = stream.getVideoTracks()[0];
  if (typeof MediaStreamTrackProcessor !== 'undefined') pumpTrack(track, wanted, hand);
  else pumpVideo(video, stream, wanted, hand);
}

async function pumpTrack(track, wanted, hand) {
  const reader = new MediaStreamTrackProcessor({ track }).readable.getReader();
  for (;;) {
    const { value: frame, done } = await reader.read();
    if (done) return;
    if (!wanted()) {
      frame.close();
      continue;
    }
    hand(frame);
  }
}

function pumpVideo(video, stream, wanted, hand) {
  const next = () => (video.requestVideoFrameCallback ? video.requestVideoFrameCallback(step) : requestAnimationFrame(step));
  const step = async () => {
    if (wanted() && video.videoWidth > 0) {
      try {
        hand(await createImageBitmap(video));
      } catch { /* this frame is lost; the next one comes */ }
    }
    if (stream.active) next();
  };
  next();
}
