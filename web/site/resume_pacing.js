// When a transfer whose connection broke is tried again (docs/PROTOCOL.md,
// "Resuming a download", "Resuming an upload"): after 0.25 s, then 0.5, 1,
// 2 and 4 s, back to 0.25 s whenever the transfer got further than ever,
// and no more once nothing got further for 30 s. Downloads and uploads
// pace alike, as umf-requester does (requester/resume_pacing.hpp).
const FIRST_MS = 250;
const LONGEST_MS = 4000;
const GIVE_UP_MS = 30000;

export class ResumePacing {
  constructor() {
    this.furthest = 0;
    this.lastFurther = Date.now();
    this.nextWait = FIRST_MS;
  }

  // The transfer stands at `bytes` (as the end that keeps them says).
  reached(bytes) {
    if (bytes <= this.furthest) return;
    this.furthest = bytes;
    this.lastFurther = Date.now();
    this.nextWait = FIRST_MS;
  }

  // Nothing got further for GIVE_UP_MS, counting the next wait.
  givenUp() {
    return Date.now() + this.nextWait - this.lastFurther > GIVE_UP_MS;
  }

  // Waits the next wait; the one after is twice as long, up to LONGEST_MS.
  async wait() {
    await new Promise((resolve) => setTimeout(resolve, this.nextWait));
    this.nextWait = Math.min(this.nextWait * 2, LONGEST_MS);
  }
}
