// Test helpers for the input log: a sample header, deterministic synthetic tick records, and a whole log in memory.
import { LogEncoder, type LogHeaderInit } from '../../server/log/log-encoder.ts';
import type { TickInputRecord } from '../../shared/sim/types.ts';

/** A header for a small synthetic session. */
export function sampleHeader(over: Partial<LogHeaderInit> = {}): LogHeaderInit & { scenarioHash: string } {
  return {
    joltVersion: '1.1.0',
    scenario: 'shape-rain',
    scenarioHash: '',
    params: { count: 40, spread: 2.5 },
    seed: 1234,
    tickRateHz: 60,
    hashEveryTicks: 1,
    checkpointEveryTicks: 0,
    createdBy: 'tests',
    ...over,
  };
}

/** A deterministic, varied tick record: players 1..players join on tick 0, walk, jump, fire; player 2 leaves at 50. */
export function sampleTick(tick: number, players = 3): TickInputRecord {
  const rec: TickInputRecord = { tick, leaves: [], joins: [], commands: [] };
  if (tick === 0) for (let p = 1; p <= players; p++) rec.joins.push({ playerId: p, name: `bot-${p} ✓` });
  if (tick === 50 && players >= 2) rec.leaves.push(2);
  for (let p = 1; p <= players; p++) {
    if (p === 2 && tick >= 50) continue;
    const phase = (tick * 7 + p * 13) % 255;
    rec.commands.push({
      playerId: p,
      input: {
        moveX: phase - 127,
        moveZ: tick % 3 === 0 ? 0 : 127 - ((tick + p) % 255),
        yaw: (tick * 331 + p * 4099) % 65536,
        pitch: ((tick * 97) % 32769) - 16384,
        buttons: (tick + p) % 16,
      },
    });
  }
  return rec;
}

/** A fake 16-hex-digit state hash for tick counter `tick`. */
export function fakeHash(tick: number): string {
  return ((tick * 2654435761) >>> 0).toString(16).padStart(8, '0') + ((tick * 40503 + 17) >>> 0).toString(16).padStart(8, '0');
}

/** Encodes a whole log: initial hash, `ticks` tick records each followed by a hash, optional checkpoints, end. */
export function buildLog(ticks: number, opts: { players?: number; checkpointEvery?: number; end?: boolean } = {}): Uint8Array {
  const enc = new LogEncoder(sampleHeader({ checkpointEveryTicks: opts.checkpointEvery ?? 0 }));
  const parts: Uint8Array[] = [enc.start(), enc.hash(0, fakeHash(0))];
  for (let t = 0; t < ticks; t++) {
    parts.push(enc.tick(sampleTick(t, opts.players ?? 3)));
    parts.push(enc.hash(t + 1, fakeHash(t + 1)));
    if (opts.checkpointEvery && (t + 1) % opts.checkpointEvery === 0) parts.push(enc.checkpoint(t + 1, new Uint8Array(100).fill(t & 0xff)));
  }
  if (opts.end ?? true) parts.push(enc.end(ticks, fakeHash(ticks)));
  const size = parts.reduce((n, p) => n + p.length, 0);
  const out = new Uint8Array(size);
  let at = 0;
  for (const p of parts) {
    out.set(p, at);
    at += p.length;
  }
  return out;
}
