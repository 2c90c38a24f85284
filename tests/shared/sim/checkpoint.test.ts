// Tests of fast checkpoints (rollback): restoring gives the same hash sequence afterwards, including windows with
// spawns, removals, bullets, joins and leaves, and after a branch with different inputs.
import { describe, expect, it } from 'vitest';
import { Button } from '../../../shared/sim/input.ts';
import type { TickInputRecord } from '../../../shared/sim/types.ts';
import { botRecords, IDLE, makeSim, record, runHashes } from './helpers/sim-helpers.ts';

const WINDOW = 30;
const SAMPLE_TICKS = [0, 12, 37, 58, 81, 100];
// Bots 1-4: bot 2 leaves at tick 75, bot 4 joins at 60; all walk, jump and fire; spheres spawn every 15 ticks.
const RECORDS = botRecords(SAMPLE_TICKS[SAMPLE_TICKS.length - 1] + WINDOW, { bots: 4, joinTicks: [0, 20, 40, 60], leaveTicks: [-1, 75, -1, -1] });

/** A different branch for the window: another join, other commands, everyone firing. */
function branch(from: TickInputRecord[], present: number[]): TickInputRecord[] {
  return from.map((r, i) => {
    const commands = present.map((playerId) => ({ playerId, input: { ...IDLE, moveX: -90, yaw: (i * 977) % 65536, buttons: Button.Fire | Button.Jump } }));
    if (i === 0) return record(r.tick, { joins: [{ playerId: 99, name: 'intruder' }], commands: [...commands, { playerId: 99, input: IDLE }] });
    return record(r.tick, { commands: [...commands, { playerId: 99, input: { ...IDLE, buttons: Button.Fire } }] });
  });
}

/** The uninterrupted session's per-tick hashes. */
async function reference(): Promise<string[]> {
  const sim = await makeSim();
  const hashes = runHashes(sim, RECORDS);
  sim.destroy();
  return hashes;
}

describe('checkpoint', () => {
  it('replays identical hashes after a restore, for checkpoints sampled across a busy session', async () => {
    const hashes = await reference();
    const sim = await makeSim();
    let kinds = new Set<string>();
    for (const t of SAMPLE_TICKS) {
      runHashes(sim, RECORDS.slice(sim.tick, t));
      const cp = sim.saveCheckpoint();
      const events: { type: string }[] = [];
      const first = runHashes(sim, RECORDS.slice(t, t + WINDOW), events as never);
      kinds = new Set([...kinds, ...events.map((e) => e.type)]);
      expect(first).toEqual(hashes.slice(t, t + WINDOW));
      sim.restoreCheckpoint(cp);
      expect(sim.tick).toBe(t);
      expect(runHashes(sim, RECORDS.slice(t, t + WINDOW))).toEqual(hashes.slice(t, t + WINDOW));
      sim.restoreCheckpoint(cp);
      cp.dispose();
    }
    // The windows really contained joins, leaves, spawns (spheres and bullets) and removals.
    expect([...kinds].sort()).toEqual(expect.arrayContaining(['bodyRemoved', 'bodySpawned', 'playerJoined', 'playerLeft']));
    sim.destroy();
  });

  it('returns to the original hashes after a branch with different inputs, joins and shots', async () => {
    const hashes = await reference();
    const sim = await makeSim();
    for (const t of SAMPLE_TICKS) {
      runHashes(sim, RECORDS.slice(sim.tick, t));
      const cp = sim.saveCheckpoint();
      const present = sim.playerIds();
      const other = runHashes(sim, branch(RECORDS.slice(t, t + WINDOW), present));
      expect(other).not.toEqual(hashes.slice(t, t + WINDOW));
      sim.restoreCheckpoint(cp);
      expect(sim.playerIds()).toEqual(present);
      expect(runHashes(sim, RECORDS.slice(t, t + WINDOW))).toEqual(hashes.slice(t, t + WINDOW));
      sim.restoreCheckpoint(cp);
      cp.dispose();
    }
    sim.destroy();
  });

  it('restores descriptors and players along with the physics', async () => {
    const sim = await makeSim();
    runHashes(sim, RECORDS.slice(0, 50));
    const cp = sim.saveCheckpoint();
    const descriptors = sim.descriptors();
    const characters = sim.characters();
    runHashes(sim, branch(RECORDS.slice(50, 80), sim.playerIds()));
    sim.restoreCheckpoint(cp);
    expect(sim.descriptors()).toEqual(descriptors);
    expect(sim.characters()).toEqual(characters);
    cp.dispose();
    sim.destroy();
  });

  it('goes forward to a later checkpoint after rolling back behind it', async () => {
    const hashes = await reference();
    const sim = await makeSim();
    runHashes(sim, RECORDS.slice(0, 20));
    const early = sim.saveCheckpoint();
    runHashes(sim, RECORDS.slice(20, 70));
    const late = sim.saveCheckpoint();
    const lateHash = sim.stateHash();
    sim.restoreCheckpoint(early);
    runHashes(sim, branch(RECORDS.slice(20, 40), sim.playerIds()));
    sim.restoreCheckpoint(late);
    expect(sim.tick).toBe(70);
    expect(sim.stateHash()).toBe(lateHash);
    expect(runHashes(sim, RECORDS.slice(70, 90))).toEqual(hashes.slice(70, 90));
    early.dispose();
    late.dispose();
    sim.destroy();
  });

  it('refuses fast checkpoints of another simulation and disposed ones', async () => {
    const a = await makeSim();
    const b = await makeSim();
    const cp = a.saveCheckpoint();
    expect(() => b.restoreCheckpoint(cp)).toThrow(/only into the simulation that saved it/);
    cp.dispose();
    expect(() => a.restoreCheckpoint(cp)).toThrow(/disposed/);
    a.destroy();
    b.destroy();
  });

  it('restores forty times, in both forms, without growing the WASM heap', async () => {
    const sim = await makeSim();
    runHashes(sim, RECORDS.slice(0, 30));
    const cp = sim.saveCheckpoint();
    const bytes = sim.saveCheckpointBytes();
    runHashes(sim, RECORDS.slice(30, 70));
    sim.restoreCheckpoint(cp);
    const free = sim.world.freeHeapBytes();
    for (let i = 0; i < 40; i++) {
      runHashes(sim, RECORDS.slice(30, 70));
      if (i % 2 === 0) sim.restoreCheckpoint(cp);
      else sim.restoreCheckpointBytes(bytes);
      sim.saveCheckpoint().dispose();
    }
    expect(Math.abs(free - sim.world.freeHeapBytes())).toBeLessThan(4096);
    cp.dispose();
    sim.destroy();
  });
});

