// A movement key shows on the first predicted frame drawn after it, also while the client's estimate of where the
// server's clock stands moves back (its smoothed round trip falling after a retransmitted pong, its jitter margin
// shrinking): the frame then fixes the next tick with the new move rather than waiting for the clock to come back.
import { describe, expect, it } from 'vitest';
import { nodePredictOptions } from '../../../cli/predict-options.ts';
import { scenario as shapeRain } from '../../../scenarios/shape-rain.ts';
import { connect, type NetClient } from '../../../sdk/index.ts';
import { Prng } from '../../../shared/sim/prng.ts';
import { Button, type InputCommand } from '../../../shared/sim/input.ts';
import { MEMORY_URL, startHarness, type Harness } from '../../server/harness.ts';

const IDLE: InputCommand = { moveX: 0, moveZ: 0, yaw: 0, pitch: 0, buttons: 0 };
const WALKS: readonly InputCommand[] = [
  { moveX: 0, moveZ: 127, yaw: 0, pitch: 0, buttons: Button.Sprint },
  { moveX: 0, moveZ: -127, yaw: 0, pitch: 0, buttons: Button.Sprint },
];
const FRAME_MS = 16;

/** Advances the manual clock a frame at a time for `ms`, drawing a predicted frame each time. */
async function frames(h: Harness, c: NetClient, ms: number): Promise<void> {
  for (let t = 0; t < ms; t += FRAME_MS) {
    h.clock.advance(FRAME_MS);
    c.predicted();
    await new Promise((resolve) => setImmediate(resolve));
  }
}

function ownZ(c: NetClient): number {
  return c.predicted()!.characters.find((ch) => ch.playerId === c.playerId)!.position.z;
}

describe('a movement key on a lossy link', () => {
  it('moves the own character on the first frame drawn after the key, for every key', async () => {
    const h = await startHarness({ scenarios: [shapeRain], params: { count: 1 }, netMode: 'predict', durability: { mode: 'off' }, resumeGraceMs: 0 });
    const rng = new Prng(21);
    // As the browser test's conditioned link: 50 ms each way, 10 ms jitter, chunks held back 200 ms by a retransmit.
    const net = h.network({ latencyMs: 50, jitterMs: 10, lossRate: 0.05, retransmitMs: 200, random: () => rng.next() });
    const c = connect(MEMORY_URL, { name: 'walker', clock: h.clock, transport: net.transport, reconnect: false, predict: nodePredictOptions({ inputDelayTicks: 0 }) });
    await frames(h, c, 3000);
    expect(c.stats().prediction!.mode).toBe('predict');

    const late: Array<{ key: number; framesUntilMove: number }> = [];
    const keys = 40;
    for (let key = 0; key < keys; key++) {
      // Stand still, then press: the frame drawn at the key's moment must already show the move.
      c.setInput(IDLE);
      await frames(h, c, 700 + 16 * (key % 7));
      const from = ownZ(c);
      c.setInput(WALKS[key % 2]);
      let drawn = 1;
      while (Math.abs(ownZ(c) - from) <= 0.005 && drawn < 60) {
        await frames(h, c, FRAME_MS);
        drawn++;
      }
      if (drawn > 1) late.push({ key, framesUntilMove: drawn });
    }
    expect(late).toEqual([]);
    const p = c.stats().prediction!;
    expect({ mode: p.mode, desyncs: p.desyncs }).toEqual({ mode: 'predict', desyncs: 0 });
    c.close();
    await frames(h, c, 100);
    await h.close();
  });

  it('keeps commands of a stick that changes every frame as far ahead as those of a held key', async () => {
    const h = await startHarness({ scenarios: [shapeRain], params: { count: 1 }, netMode: 'predict', durability: { mode: 'off' }, resumeGraceMs: 0 });
    const net = h.network({ latencyMs: 40 });
    const [stick, held] = ['stick', 'held'].map((name) => connect(MEMORY_URL, { name, clock: h.clock, transport: net.transport, reconnect: false, predict: nodePredictOptions({ inputDelayTicks: 0 }) }));
    held.setInput(WALKS[0]);
    // Frames every 7 ms (a 144 Hz display), the stick's x axis different on each.
    let aheadMax = 0;
    for (let i = 0; i < 600; i++) {
      stick.setInput({ moveX: (i % 200) - 100, moveZ: 127, yaw: 0, pitch: 0, buttons: 0 });
      h.clock.advance(7);
      stick.predicted();
      held.predicted();
      await new Promise((resolve) => setImmediate(resolve));
      if (i > 300) aheadMax = Math.max(aheadMax, stick.stats().newestInputTick - held.stats().newestInputTick);
    }
    expect(stick.stats().prediction!.mode).toBe('predict');
    // The held key's client fixed its ticks when the clock asked; the stick's may fix one tick before that, no more.
    expect(aheadMax).toBeLessThanOrEqual(1);
    for (const c of [stick, held]) c.close();
    for (let i = 0; i < 20; i++) {
      h.clock.advance(10);
      await new Promise((resolve) => setImmediate(resolve));
    }
    await h.close();
  });
});
