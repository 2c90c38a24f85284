// A one-line progress bar on stderr, drawn only when stderr is a terminal and redrawn at most ten times a second.
import type { CliIo } from './command.ts';

/** Draws and clears a progress bar; every method is a no-op when stderr is not a TTY. */
export class ProgressBar {
  private readonly io: CliIo;
  private readonly label: string;
  private lastDrawMs = -Infinity;
  private drawn = false;

  constructor(io: CliIo, label: string) {
    this.io = io;
    this.label = label;
  }

  /** Shows `fraction` (0…1) done and a short note. */
  update(fraction: number, note: string): void {
    if (!this.io.stderrIsTTY) return;
    const now = performance.now();
    if (now - this.lastDrawMs < 100) return;
    this.lastDrawMs = now;
    const f = Math.min(1, Math.max(0, fraction));
    const width = 30;
    const full = Math.round(f * width);
    this.io.stderr(`\r${this.label} [${'#'.repeat(full)}${'-'.repeat(width - full)}] ${(f * 100).toFixed(0).padStart(3)}% ${note}\x1b[K`);
    this.drawn = true;
  }

  /** Erases the bar (call before printing results). */
  clear(): void {
    if (this.drawn) this.io.stderr('\r\x1b[K');
    this.drawn = false;
  }
}
