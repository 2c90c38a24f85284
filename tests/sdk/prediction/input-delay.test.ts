// Predicted play's input delay: the room announces a default in the welcome (serve --input-delay-ticks), a client may
// choose its own; own commands go out for ticks that much later, and the own move shows that many ticks later.
import { describe, expect, it } from 'vitest';
import { nodePredictOptions } from '../../../cli/predict-options.ts';
import { scenario as shapeRain } from '../../../scenarios/shape-rain.ts';
import { connect, type NetClient } from '../../../sdk/index.ts';
import { Button, type InputCommand } from '../../../shared/sim/input.ts';
import type { TickInputRecord } from '../../../shared/sim/types.ts';
import { MEMORY_URL, startHarness, type Harness } from '../../server/harness.ts';

async function play(h: Harness, ms: number, each?: () => void): Promise<void> {
  for (let t = 0; t < ms; t += 4) {
    h.clock.advance(4);
    each?.();
    await new Promise((resolve) => setImmediate(resolve));
  }
}

const WALK: InputCommand = { moveX: 0, moveZ: 127, yaw: 0, pitch: 0, buttons: Button.Sprint };

/**
 * Sets WALK and draws frames 1 ms apart until the own character moved: how many frames that took (1: the first, drawn
 * at once) and how many ticks past the present at the key that frame is.
 */
async function ticksUntilOwnMove(h: Harness, c: NetClient): Promise<{ frames: number; ticks: number; keyTick: number }> {
  const own = (): number => c.predicted()!.characters.find((ch) => ch.playerId === c.playerId)!.position.z;
  const from = own();
  const presentAtKey = c.predicted()!.tick;
  const keyTick = c.stats().newestInputTick + 1;
  c.setInput(WALK);
  for (let i = 0; i < 500; i++) {
    const frame = c.predicted()!;
    if (Math.abs(own() - from) > 0.005) return { frames: i + 1, ticks: frame.tick - presentAtKey, keyTick };
    h.clock.advance(1);
    await new Promise((resolve) => setImmediate(resolve));
  }
  throw new Error('the own character never moved');
}

describe('input delay', () => {
  it("applies the room's announced delay, or the client's own, to own commands", async () => {
    const h = await startHarness({ scenarios: [shapeRain], params: { count: 1 }, netMode: 'predict', inputDelayTicks: 3, durability: { mode: 'off' }, resumeGraceMs: 0 });
    const records = new Map<number, TickInputRecord>();
    const net = h.network({ latencyMs: 30 });
    const room = connect(MEMORY_URL, { name: 'room-delay', clock: h.clock, transport: net.transport, reconnect: false, predict: nodePredictOptions() });
    const none = connect(MEMORY_URL, { name: 'no-delay', clock: h.clock, transport: net.transport, reconnect: false, predict: nodePredictOptions({ inputDelayTicks: 0 }) });
    await play(h, 1500, () => {
      room.predicted();
      none.predicted();
    });
    h.room().onTick((record) => records.set(record.tick, structuredClone(record)));
    expect(room.welcome!.inputDelayTicks).toBe(3);
    expect(room.stats().prediction!.inputDelayTicks).toBe(3);
    expect(none.stats().prediction!.inputDelayTicks).toBe(0);

    // Without delay the first frame after the key, drawn at once, has simulated it; with 3 ticks, the move shows 3
    // ticks later.
    const direct = await ticksUntilOwnMove(h, none);
    expect(direct).toMatchObject({ frames: 1, ticks: 1 });
    const delayed = await ticksUntilOwnMove(h, room);
    expect(delayed.ticks).toBe(4);
    // The command went out for its tick and the server applied it there.
    await play(h, 500);
    const applied = (tick: number): InputCommand | undefined => records.get(tick)?.commands.find((c) => c.playerId === room.playerId)?.input;
    expect(applied(delayed.keyTick)).toEqual(WALK);
    expect(applied(delayed.keyTick - 1)?.moveZ).toBe(0);
    for (const c of [room, none]) expect(c.stats().prediction!.desyncs).toBe(0);
    for (const c of [room, none]) c.close();
    await play(h, 100);
    await h.close();
  });

  it('announces no delay in snapshot rooms and refuses a bad client delay', async () => {
    const h = await startHarness({ scenarios: [shapeRain], params: { count: 1 }, netMode: 'snapshot', inputDelayTicks: 3, resumeGraceMs: 0 });
    const net = h.network({ latencyMs: 10 });
    const c = connect(MEMORY_URL, { name: 'snap', clock: h.clock, transport: net.transport, reconnect: false });
    await play(h, 300);
    expect(c.welcome!.inputDelayTicks).toBe(0);
    expect(() => connect(MEMORY_URL, { name: 'bad', transport: net.transport, predict: nodePredictOptions({ inputDelayTicks: 16 }) })).toThrow(/inputDelayTicks must be an integer in \[0, 15\]/);
    c.close();
    await play(h, 100);
    await h.close();
  });
});
