// Measures key → own motion on screen: a movement key pressed while the own character stands still starts a
// measurement; the first drawn frame that shows the character moved ends it (frames drawn since the key, ms, and the
// frames that drew a newer tick than the key's without the move). Feeds the test hook and the latency figures;
// touches neither input nor rendering.

/** Metres the drawn character must move before the key counts as shown (quantization noise stays below it). */
const MOVED_METRES = 0.005;

/** One measured key → motion. */
export interface KeyToMotion {
  /** Frames drawn after the key up to and including the first that shows the move (1: the very next frame). */
  frames: number;
  /** Milliseconds from the key event to the end of drawing that frame. */
  ms: number;
  /**
   * Frames drawn after the key that showed a later tick than the last frame before it, yet not the move: 0 when the
   * first simulated tick after the key already carries it (predicted play); the server's round trip otherwise.
   */
  staleFrames: number;
}

type Vec3 = readonly [number, number, number];

function distance(a: Vec3, b: Vec3): number {
  return Math.hypot(a[0] - b[0], a[1] - b[1], a[2] - b[2]);
}

/** Tracks one pending measurement at a time; keeps the last result and how many were taken. */
export class KeyToMotionMeter {
  private pending: { atMs: number; framesAtKey: number; tickAtKey: number; from: Vec3; stale: number } | null = null;
  private lastTick = 0;
  private lastDrawn: Vec3 | null = null;
  /** Whether the last two frames drew the own character in the same place. */
  private still = false;
  /** The last measurement. */
  last: KeyToMotion | null = null;
  /** Measurements taken. */
  count = 0;

  /** A movement key went down at `atMs`; starts a measurement when the own character was drawn standing still. */
  keyDown(atMs: number, framesRendered: number): void {
    if (this.pending || !this.lastDrawn || !this.still) return;
    this.pending = { atMs, framesAtKey: framesRendered, tickAtKey: this.lastTick, from: this.lastDrawn, stale: 0 };
  }

  /** A frame was drawn (framesRendered counts it) showing `tick`, the own character at `position` (null: none). */
  frameDrawn(nowMs: number, framesRendered: number, tick: number, position: Vec3 | null): void {
    this.lastTick = tick;
    if (position === null) {
      this.lastDrawn = null;
      this.still = false;
      this.pending = null;
      return;
    }
    const p = this.pending;
    if (p && distance(position, p.from) > MOVED_METRES) {
      this.last = { frames: framesRendered - p.framesAtKey, ms: nowMs - p.atMs, staleFrames: p.stale };
      this.count++;
      this.pending = null;
    } else if (p && tick > p.tickAtKey) {
      p.stale++;
    }
    this.still = this.lastDrawn !== null && distance(position, this.lastDrawn) <= MOVED_METRES;
    this.lastDrawn = [position[0], position[1], position[2]];
  }
}
