// Tests of the Predictor over real simulations, without a network: a server simulation steps a bot session with
// joins, leaves, shots (spawns and removals) and constant turning, its coded records reach the predictor 8 ticks late
// while the predictor runs 4 ticks ahead; every confirmed event and hash must be the server's, and mispredictions
// must roll back.
import { describe, expect, it } from 'vitest';
import '../../../server/physics-node.ts';
import { scenario as characterCourse } from '../../../scenarios/character-course.ts';
import { Predictor } from '../../../sdk/prediction/predictor.ts';
import { carriesHash, type RecordMessage } from '../../../shared/protocol/predict-messages.ts';
import { RecordDeltaCoder } from '../../../shared/protocol/record-delta.ts';
import { BotScript } from '../../../shared/sim/bots.ts';
import { Simulation } from '../../../shared/sim/simulation.ts';
import type { SimEvent } from '../../../shared/sim/types.ts';

const TICKS = 240;
const DELAY_TICKS = 8;
const AHEAD_TICKS = 4;
const OWN = 1;

describe('predictor', () => {
  for (const every of [1, 4]) {
  it(`confirms the server events and hashes through joins, leaves, spawns and removals inside the rollback window (a checkpoint every ${every} ticks)`, async () => {
    const records = new BotScript({ seed: 21, bots: 4, joinTicks: [0, 30, 33, 90], leaveTicks: [-1, 120, -1, 200] }).take(TICKS + DELAY_TICKS + AHEAD_TICKS);
    const server = await Simulation.create({ scenario: characterCourse, seed: 2 });
    const client = await Simulation.create({ scenario: characterCourse, seed: 2 });
    const coder = new RecordDeltaCoder();
    const serverEvents: SimEvent[] = [];
    const clientEvents: SimEvent[] = [];
    const desyncs: string[] = [];
    const predictor = new Predictor(client, { tick: 0, inputs: [] }, OWN, { confirmedEvents: (e) => clientEvents.push(...e), desync: (t, a, b) => desyncs.push(`${t}: ${a} ≠ ${b}`) }, 30, every);
    const ownCommand = (tick: number) => records[tick].commands.find((c) => c.playerId === OWN)?.input;
    const wire: RecordMessage[] = [];
    let rollbacks = 0;
    let deepest = 0;
    try {
      for (let t = 0; t < TICKS; t++) {
        serverEvents.push(...server.step(records[t]));
        const { bits, joins } = coder.encode(records[t]);
        wire.push({ type: 'record', tickLow: t & 0xff, bits, joins, hash: carriesHash(t) ? server.stateHash() : null });
        if (t >= DELAY_TICKS) predictor.receive(wire[t - DELAY_TICKS]);
        const report = predictor.advance(t + AHEAD_TICKS, ownCommand);
        if (report.corrected) rollbacks++;
        deepest = Math.max(deepest, report.rollbackTicks);
      }
      for (let t = TICKS - DELAY_TICKS; t < TICKS; t++) predictor.receive(wire[t]);
      predictor.advance(TICKS, ownCommand);
      expect(desyncs).toEqual([]);
      expect(predictor.confirmedTick).toBe(TICKS);
      expect(predictor.presentTick).toBe(TICKS - 1 + AHEAD_TICKS);
      expect(predictor.hashesVerified).toBe(TICKS / 30);
      expect(clientEvents).toEqual(serverEvents);
      expect(new Set(serverEvents.map((e) => e.type))).toEqual(expect.objectContaining(new Set(['playerJoined', 'playerLeft', 'bodySpawned', 'bodyRemoved'])));
      expect(rollbacks).toBeGreaterThan(TICKS / 2);
      expect(deepest).toBeGreaterThanOrEqual(DELAY_TICKS + AHEAD_TICKS - 1);
    } finally {
      predictor.dispose();
      server.destroy();
      client.destroy();
    }
  });
  }

  it('stops predicting further ahead than its window and catches up from confirmed records', async () => {
    const records = new BotScript({ seed: 5, bots: 2, joinSpacingTicks: 0 }).take(80);
    const server = await Simulation.create({ scenario: characterCourse });
    const client = await Simulation.create({ scenario: characterCourse });
    const coder = new RecordDeltaCoder();
    const predictor = new Predictor(client, { tick: 0, inputs: [] }, 1, { confirmedEvents: () => {}, desync: () => {} }, 10);
    try {
      predictor.advance(50, () => undefined);
      expect(predictor.presentTick).toBe(10);
      for (const r of records) {
        server.step(r);
        const { bits, joins } = coder.encode(r);
        predictor.receive({ type: 'record', tickLow: r.tick & 0xff, bits, joins, hash: null });
      }
      expect(() => predictor.receive({ type: 'record', tickLow: 3, bits: new Uint8Array(1), joins: [], hash: null })).toThrow(/tick 80 was expected/);
      predictor.advance(85, () => undefined);
      expect(predictor.confirmedTick).toBe(80);
      expect(predictor.presentTick).toBe(85);
      client.restoreCheckpointBytes(server.saveCheckpointBytes());
      expect(client.stateHash()).toBe(server.stateHash());
    } finally {
      predictor.dispose();
      server.destroy();
      client.destroy();
    }
  });
});
