// Tests of the checkpoint byte form: restoring into a fresh simulation (another "process") and into a diverged one
// continues with identical hashes; corrupt, truncated, foreign or future-version bytes are refused and change nothing.
import { createHash } from 'node:crypto';
import { describe, expect, it } from 'vitest';
import { CHECKPOINT_FORMAT_VERSION } from '../../../shared/sim/checkpoint-codec.ts';
import { Button } from '../../../shared/sim/input.ts';
import { testArena, testArenaPvp } from './helpers/test-scenarios.ts';
import { botRecords, IDLE, makeSim, record, runHashes } from './helpers/sim-helpers.ts';

const RECORDS = botRecords(140, { bots: 3, joinTicks: [0, 10, 50], leaveTicks: [-1, 60, -1] });

describe('checkpoint-codec', () => {
  it('restores into a fresh simulation of the same setup and continues with identical hashes', async () => {
    const original = await makeSim();
    const hashes = runHashes(original, RECORDS);
    const source = await makeSim();
    runHashes(source, RECORDS.slice(0, 70));
    const bytes = source.saveCheckpointBytes();
    const fresh = await makeSim();
    fresh.restoreCheckpointBytes(bytes);
    expect(fresh.tick).toBe(70);
    expect(fresh.stateHash()).toBe(hashes[69]);
    expect(fresh.descriptors()).toEqual(source.descriptors());
    expect(runHashes(fresh, RECORDS.slice(70))).toEqual(hashes.slice(70));
    for (const s of [original, source, fresh]) s.destroy();
  });

  it('restores into the simulation that saved it after it went down another branch', async () => {
    const sim = await makeSim(testArenaPvp);
    runHashes(sim, RECORDS.slice(0, 40));
    const bytes = sim.saveCheckpointBytes();
    const after = runHashes(sim, RECORDS.slice(40, 80));
    sim.restoreCheckpointBytes(bytes);
    const shots = Array.from({ length: 30 }, (_, i) =>
      record(40 + i, { commands: sim.playerIds().map((playerId) => ({ playerId, input: { ...IDLE, moveZ: 127, buttons: Button.Fire } })) }),
    );
    runHashes(sim, shots);
    sim.restoreCheckpointBytes(bytes);
    expect(runHashes(sim, RECORDS.slice(40, 80))).toEqual(after);
    sim.destroy();
  });

  it('writes the same bytes as ever for a known session (format pin: length and SHA-256)', async () => {
    const sim = await makeSim(testArenaPvp, { boxes: 3 }, 'pin');
    runHashes(sim, RECORDS.slice(0, 70));
    const bytes = sim.saveCheckpointBytes();
    expect({ sizeBytes: bytes.length, sha256: createHash('sha256').update(bytes).digest('hex') }).toEqual({ sizeBytes: 5056, sha256: 'dce2fbb5443cf992298096033aca6dfa39a1b3e45ff4a518f6319648724b6ccd' });
    sim.destroy();
  });

  it('is self-describing: magic, format version, then the setup it belongs to', async () => {
    const sim = await makeSim(testArena, { boxes: 3 }, 'seed text');
    const bytes = sim.saveCheckpointBytes();
    expect(new TextDecoder().decode(bytes.subarray(0, 8))).toBe('TAOSCKPT');
    expect(new DataView(bytes.buffer).getUint32(8, true)).toBe(CHECKPOINT_FORMAT_VERSION);
    expect(new TextDecoder().decode(bytes.subarray(16, 16 + 'test-arena'.length))).toBe('test-arena');
    sim.destroy();
  });

  it('refuses a flipped byte, a truncated file and foreign data, leaving the simulation untouched', async () => {
    const sim = await makeSim();
    runHashes(sim, RECORDS.slice(0, 30));
    const bytes = sim.saveCheckpointBytes();
    runHashes(sim, RECORDS.slice(30, 35));
    const before = sim.stateHash();
    const flipped = bytes.slice();
    flipped[Math.floor(bytes.length / 2)] ^= 0x10;
    expect(() => sim.restoreCheckpointBytes(flipped)).toThrow(/checksum mismatch/);
    expect(() => sim.restoreCheckpointBytes(bytes.subarray(0, bytes.length - 100))).toThrow(/checksum mismatch|truncated/);
    expect(() => sim.restoreCheckpointBytes(new Uint8Array(40))).toThrow(/not a taos-physics checkpoint/);
    expect(() => sim.restoreCheckpointBytes(new Uint8Array(5))).toThrow(/too short/);
    const future = bytes.slice();
    new DataView(future.buffer).setUint32(8, CHECKPOINT_FORMAT_VERSION + 1, true);
    expect(() => sim.restoreCheckpointBytes(future)).toThrow(/format version 2, this build reads 1/);
    expect(sim.tick).toBe(35);
    expect(sim.stateHash()).toBe(before);
    expect(() => sim.step(RECORDS[35])).not.toThrow();
    sim.destroy();
  });

  it('refuses a checkpoint of another scenario, other parameters or another seed', async () => {
    const a = await makeSim(testArena, { boxes: 3 }, 5);
    const bytes = a.saveCheckpointBytes();
    const otherSeed = await makeSim(testArena, { boxes: 3 }, 6);
    const otherParams = await makeSim(testArena, { boxes: 4 }, 5);
    const otherScenario = await makeSim(testArenaPvp, { boxes: 3 }, 5);
    for (const s of [otherSeed, otherParams, otherScenario]) {
      expect(() => s.restoreCheckpointBytes(bytes)).toThrow(/the checkpoint is for test-arena/);
      s.destroy();
    }
    a.destroy();
  });
});

describe('checkpoint-codec body options', () => {
  it('carries JSON userData of spawned bodies and refuses userData it cannot store', async () => {
    let payload: unknown = { kind: 'target', points: [1, 2] };
    const def = {
      ...testArena,
      build: (ctx: Parameters<typeof testArena.build>[0]) => {
        const inner = testArena.build(ctx);
        return { ...inner, onTick: (c: typeof ctx) => void (c.tick === 1 && c.spawn({ kind: 'sphere', radius: 0.3 }, { x: 0, y: 4, z: 0 }, null, { userData: payload })) };
      },
    };
    const sim = await makeSim(def);
    runHashes(sim, [record(0), record(1), record(2)]);
    const fresh = await makeSim(def);
    fresh.restoreCheckpointBytes(sim.saveCheckpointBytes());
    const spawned = fresh.descriptors().find((d) => d.shape.kind === 'sphere')!;
    expect(fresh.world.getBody(spawned.id)!.userData).toEqual({ kind: 'target', points: [1, 2] });
    payload = { onHit: () => 1 };
    const other = await makeSim(def);
    runHashes(other, [record(0), record(1)]);
    expect(() => other.saveCheckpointBytes()).toThrow(/userData\) are not plain JSON data: "onHit" holds a function/);
    for (const s of [sim, fresh, other]) s.destroy();
  });
});
