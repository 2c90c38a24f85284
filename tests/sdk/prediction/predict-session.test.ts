// Tests of PredictSession without a network: it asks for predict mode, starts from the checkpoint, answers a hash
// mismatch with a resync (counting a desync), and falls back to snapshots when every frame stays over its budget.
import { describe, expect, it } from 'vitest';
import { nodePredictOptions } from '../../../cli/predict-options.ts';
import { scenario as characterCourse } from '../../../scenarios/character-course.ts';
import { PredictSession, type PredictLink } from '../../../sdk/prediction/predict-session.ts';
import type { PredictSimulation } from '../../../sdk/prediction/predictor.ts';
import type { ClientMessage } from '../../../shared/protocol/client-messages.ts';
import { carriesHash, type CheckpointMessage } from '../../../shared/protocol/predict-messages.ts';
import { RecordDeltaCoder } from '../../../shared/protocol/record-delta.ts';
import type { WelcomeMessage } from '../../../shared/protocol/server-messages.ts';
import { BotScript } from '../../../shared/sim/bots.ts';
import { Simulation } from '../../../shared/sim/simulation.ts';

const welcome = { playerId: 1, scenario: { name: 'character-course', description: '', params: {}, bounds: characterCourse.bounds }, netMode: 'predict', inputDelayTicks: 0 } as unknown as WelcomeMessage;

function link(clock: { ms: number }): PredictLink & { sent: ClientMessage[]; errors: string[]; fellBackWith: string | null } {
  const l = {
    sent: [] as ClientMessage[],
    errors: [] as string[],
    fellBackWith: null as string | null,
    send: (m: ClientMessage) => l.sent.push(m),
    nowMs: () => clock.ms,
    events: () => {},
    gameState: () => {},
    protocolError: (m: string) => l.errors.push(m),
    fellBack: (reason: string) => (l.fellBackWith = reason),
  };
  return l;
}

async function checkpointOf(sim: Simulation): Promise<CheckpointMessage> {
  return { type: 'checkpoint', tick: sim.tick, seed: 1, bytes: sim.saveCheckpointBytes(), inputs: [] };
}

async function settle(until: () => boolean): Promise<void> {
  for (let i = 0; i < 500 && !until(); i++) await new Promise((resolve) => setTimeout(resolve, 5));
}

describe('predict-session', () => {
  it('resyncs on a hash mismatch and counts the desync', async () => {
    const clock = { ms: 0 };
    const l = link(clock);
    const server = await Simulation.create({ scenario: characterCourse });
    const session = new PredictSession(welcome, nodePredictOptions(), l);
    try {
      expect(l.sent).toEqual([{ type: 'netMode', mode: 'predict' }]);
      session.onCheckpoint(await checkpointOf(server));
      await settle(() => session.stats().mode === 'predict');
      expect(session.stats().mode).toBe('predict');
      const coder = new RecordDeltaCoder();
      const bots = new BotScript({ seed: 1, bots: 2, joinSpacingTicks: 0 });
      for (let t = 0; t < 30; t++) {
        const r = bots.next();
        server.step(r);
        const { bits, joins } = coder.encode(r);
        // The server's hash of tick 29 is corrupted on the wire.
        session.onRecord({ type: 'record', tickLow: t, bits, joins, hash: carriesHash(t) ? '0000000000000000' : null });
        clock.ms += 8;
        session.advance(t + 3, () => undefined);
      }
      expect(session.stats()).toMatchObject({ mode: 'resyncing', desyncs: 1 });
      expect(l.sent.at(-1)).toEqual({ type: 'resync' });
      expect(l.errors[0]).toMatch(/desync at tick 29/);
      session.onCheckpoint(await checkpointOf(server));
      await settle(() => session.stats().mode === 'predict');
      expect(session.stats()).toMatchObject({ mode: 'predict', resyncs: 1, confirmedTick: 30 });
    } finally {
      session.dispose();
      server.destroy();
    }
  });

  it('falls back to snapshots when every frame stays over budget for the fallback time', async () => {
    const clock = { ms: 0 };
    const l = link(clock);
    const server = await Simulation.create({ scenario: characterCourse });
    // A simulation whose every tick takes 10 ms of the session's clock.
    const slow = nodePredictOptions({ frameBudgetMs: 16, fallbackAfterMs: 200 });
    const session = new PredictSession(welcome, {
      ...slow,
      createSimulation: async (setup) => {
        const sim = (await slow.createSimulation(setup)) as PredictSimulation;
        const step = sim.step.bind(sim);
        sim.step = (r) => {
          clock.ms += 10;
          return step(r);
        };
        return sim;
      },
    }, l);
    try {
      session.onCheckpoint(await checkpointOf(server));
      await settle(() => session.stats().mode === 'predict');
      let target = 0;
      for (let frame = 0; frame < 100 && session.active; frame++) {
        target += 2;
        session.advance(target, () => undefined);
      }
      expect(session.active).toBe(false);
      expect(session.stats().mode).toBe('snapshot');
      expect(l.fellBackWith).toMatch(/over the 16\.0 ms budget/);
      expect(l.sent.at(-1)).toEqual({ type: 'netMode', mode: 'snapshot' });
      expect(session.frame()).toBeNull();
    } finally {
      session.dispose();
      server.destroy();
    }
  });
});
