// Measures key → own motion on screen: a movement key pressed while the own character stands still starts a
// measurement; the first drawn frame that shows the character moved ends it (frames drawn since the key, and ms).
// Feeds the HUD-free test hook and the latency figures; touches neither input nor rendering.

/** Metres the drawn character must move before the key counts as shown (quantization noise stays below it). */
const MOVED_METRES = 0.005;

/** One measured key → motion. */
export interface KeyToMotion {
  /** Frames drawn after the key up to and including the first that shows the move (1: the very next frame). */
  frames: number;
  /** Milliseconds from the key event to the end of drawing that frame. */
  ms: number;
}

type Vec3 = readonly [number, number, number];

function distance(a: Vec3, b: Vec3): number {
  return Math.hypot(a[0] - b[0], a[1] - b[1], a[2] - b[2]);
}

/** Tracks one pending measurement at a time; keeps the last result and how many were taken. */
export class KeyToMotionMeter {
  private pending: { atMs: number; framesAtKey: number; from: Vec3 } | null = null;
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
    this.pending = { atMs, framesAtKey: framesRendered, from: this.lastDrawn };
  }

  /** A frame was drawn (framesRendered counts it) with the own character at `position` (null: none drawn). */
  frameDrawn(nowMs: number, framesRendered: number, position: Vec3 | null): void {
    if (position === null) {
      this.lastDrawn = null;
      this.still = false;
      this.pending = null;
      return;
    }
    const p = this.pending;
    if (p && distance(position, p.from) > MOVED_METRES) {
      this.last = { frames: framesRendered - p.framesAtKey, ms: nowMs - p.atMs };
      this.count++;
      this.pending = null;
    }
    this.still = this.lastDrawn !== null && distance(position, this.lastDrawn) <= MOVED_METRES;
    this.lastDrawn = [position[0], position[1], position[2]];
  }
}
