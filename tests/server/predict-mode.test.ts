// Tests of predict mode on the server, over the in-process harness: a client that asks for predict gets a checkpoint
// and then one record per tick (no snapshots, no events) that rebuilds the room's exact records and hashes; resyncs
// are limited to one a second; snapshot rooms refuse predict; a predicting client can fall back to snapshots.
import { afterEach, describe, expect, it } from 'vitest';
import { RecordDeltaCoder } from '../../shared/protocol/record-delta.ts';
import { ErrorCode } from '../../shared/protocol/opcodes.ts';
import { NEUTRAL_INPUT } from '../../shared/sim/input.ts';
import { startHarness, type Harness } from './harness.ts';
import { stripScenario } from './test-scenarios.ts';

let h: Harness | null = null;
afterEach(async () => {
  await h?.close();
  h = null;
});

describe('predict mode (server)', () => {
  it('sends a predicting client a checkpoint, then every tick its record and every 30 ticks the hash', async () => {
    h = await startHarness({ scenarios: [stripScenario], netMode: 'predict' });
    expect(h.room().info()).toMatchObject({ netMode: 'predict' });
    const watcher = await h.join('watcher');
    const c = await h.join('ann');
    expect(c.welcome!.netMode).toBe('predict');
    h.ticks(5);
    c.send({ type: 'netMode', mode: 'predict' });
    h.ticks(1);
    const cp = c.ofType('checkpoint');
    expect(cp).toHaveLength(1);
    expect(cp[0].seed).toBe(1);
    expect(cp[0].inputs.map((p) => p.playerId)).toEqual([watcher.playerId, c.playerId]);
    const snapshotsBefore = c.ofType('snapshot').length;
    const eventsBefore = c.ofType('events').length;
    c.input(h.room().sim.tick + 1, [{ ...NEUTRAL_INPUT, moveZ: 100, yaw: 300 }]);
    h.ticks(70);
    expect(c.ofType('snapshot').length).toBe(snapshotsBefore);
    expect(c.ofType('events').length).toBe(eventsBefore);
    const records = c.ofType('record');
    expect(records.length).toBeGreaterThanOrEqual(70);
    const { records: stepped, hashes } = h.history();
    const coder = new RecordDeltaCoder(cp[0].inputs);
    let hashes30 = 0;
    records.forEach((m, i) => {
      const tick = cp[0].tick + i;
      expect(m.tickLow).toBe(tick & 0xff);
      expect(coder.decode(tick, m.bits, m.joins)).toEqual(stepped[tick]);
      if (m.hash !== null) {
        expect((tick + 1) % 30).toBe(0);
        expect(m.hash).toBe(hashes[tick]);
        hashes30++;
      }
    });
    expect(hashes30).toBeGreaterThanOrEqual(2);
    // The watcher (no netMode request) is still served snapshots.
    expect(watcher.ofType('snapshot').length).toBeGreaterThan(30);
    expect(watcher.ofType('record')).toHaveLength(0);
  });

  it('answers one resync a second and refuses the rest as rate-limited', async () => {
    h = await startHarness({ scenarios: [stripScenario], netMode: 'predict' });
    const c = await h.join('ann');
    c.send({ type: 'resync' });
    h.ticks(1);
    expect(c.ofType('error').at(-1)).toMatchObject({ code: ErrorCode.UnexpectedMessage });
    c.send({ type: 'netMode', mode: 'predict' });
    c.send({ type: 'resync' });
    h.ticks(1);
    expect(c.ofType('checkpoint')).toHaveLength(1);
    expect(c.ofType('error').at(-1)).toMatchObject({ code: ErrorCode.RateLimited });
    h.ticks(70);
    c.send({ type: 'resync' });
    h.ticks(1);
    expect(c.ofType('checkpoint')).toHaveLength(2);
    expect(c.ofType('checkpoint')[1].tick).toBeGreaterThan(c.ofType('checkpoint')[0].tick + 60);
  });

  it('refuses predict in a snapshot room and serves a predicting client snapshots again after netMode snapshot', async () => {
    h = await startHarness({ scenarios: [stripScenario], netMode: 'snapshot' });
    const a = await h.join('ann');
    expect(a.welcome!.netMode).toBe('snapshot');
    a.send({ type: 'netMode', mode: 'predict' });
    h.ticks(1);
    expect(a.ofType('error').at(-1)).toMatchObject({ code: ErrorCode.UnexpectedMessage, message: expect.stringContaining('serves snapshots only') });
    await h.close();

    h = await startHarness({ scenarios: [stripScenario], netMode: 'predict' });
    const b = await h.join('bob');
    b.send({ type: 'netMode', mode: 'predict' });
    h.ticks(10);
    const snapshots = b.ofType('snapshot').length;
    b.send({ type: 'netMode', mode: 'snapshot' });
    h.ticks(10);
    const after = b.ofType('snapshot').slice(snapshots);
    expect(after.length).toBeGreaterThan(2);
    // The first snapshot after the switch describes every body the client will draw.
    expect(after[0].descriptors.length).toBeGreaterThan(0);
    const records = b.ofType('record').length;
    h.ticks(10);
    expect(b.ofType('record').length).toBe(records);
  });
});
