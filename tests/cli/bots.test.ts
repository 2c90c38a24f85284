// Tests for cli/bots.ts: seeded scripted bots join through the client library (MemoryNetwork, manual clock),
// drive varied commands into the room, stop on time and report their traffic; with a scenario of your own they predict.
import { afterEach, describe, expect, it } from 'vitest';
import { startBots } from '../../cli/bots.ts';
import { nodePredictOptions } from '../../cli/predict-options.ts';
import { scenario as ballGoals } from '../../examples/ball-goals/game.ts';
import { MEMORY_URL, startHarness, type Harness } from '../server/harness.ts';
import { stripScenario } from '../server/test-scenarios.ts';

let h: Harness | null = null;
afterEach(async () => {
  await h?.close();
  h = null;
});

describe('bots', () => {
  it('joins N scripted bots that walk, turn, jump and fire, then stops and reports', async () => {
    h = await startHarness({ scenarios: [stripScenario] });
    const net = h.network({ latencyMs: 20 });
    const run = startBots({ url: MEMORY_URL, count: 3, seconds: 4, clock: h.clock, transport: net.transport, seed: 7 });
    let report: Awaited<typeof run.done> | null = null;
    void run.done.then((r) => (report = r));
    await h.settle(() => h!.room().clientCount === 3);
    expect(h.room().clientCount).toBe(3);
    await h.settle(() => report !== null, 10_000);
    const r = report!;
    expect(r.bots.map((b) => b.connected)).toEqual([true, true, true]);
    expect(r.bots.every((b) => b.snapshots > 50 && b.bytesIn > 0 && b.bytesOut > 0)).toBe(true);
    expect(r.bots.every((b) => b.closedReason === 'client-closed')).toBe(true);
    expect(r.kbpsInPerBot).toBeGreaterThan(0);
    // The room applied their scripts: moving, turning and button presses (jump/fire) from every bot.
    const commands = h.history().records.flatMap((rec) => rec.commands);
    for (const id of [1, 2, 3]) {
      const mine = commands.filter((c) => c.playerId === id).map((c) => c.input);
      expect(new Set(mine.map((c) => c.yaw)).size).toBeGreaterThan(10);
      expect(mine.some((c) => c.moveZ !== 0)).toBe(true);
      expect(mine.some((c) => c.buttons !== 0)).toBe(true);
    }
    await h.settle(() => h!.room().clientCount === 0);
    expect(h.room().clientCount).toBe(0);
  });

  it('reports bots that the server refuses', async () => {
    h = await startHarness({ scenarios: [stripScenario] });
    const net = h.network();
    const run = startBots({ url: MEMORY_URL, count: 2, room: 'no-such-room', seconds: 1, clock: h.clock, transport: net.transport });
    let report: Awaited<typeof run.done> | null = null;
    void run.done.then((r) => (report = r));
    await h.settle(() => report !== null, 5000);
    expect(report!.bots.map((b) => [b.connected, b.closedReason])).toEqual([
      [false, 'room-not-found'],
      [false, 'room-not-found'],
    ]);
  });

  it('reports the server\'s room-full refusal with its words, not a client close', async () => {
    h = await startHarness({ scenarios: [stripScenario], maxClientsPerRoom: 1 });
    const net = h.network();
    const run = startBots({ url: MEMORY_URL, count: 2, seconds: 2, clock: h.clock, transport: net.transport });
    let report: Awaited<typeof run.done> | null = null;
    void run.done.then((r) => (report = r));
    await h.settle(() => report !== null, 5000);
    const [first, second] = report!.bots;
    expect([first.connected, first.closedReason]).toEqual([true, 'client-closed']);
    expect([second.connected, second.closedReason]).toEqual([false, 'room-full']);
    expect(second.closedDetail).toMatch(/^room-full: room default is full \(1 clients\)/);
  });

  it('predicts a room of a scenario of your own (a game-API game) when given its definition, without a desync', async () => {
    h = await startHarness({ scenarios: [ballGoals], durability: { mode: 'off' } });
    expect(h.room().netMode).toBe('predict');
    const net = h.network({ latencyMs: 30 });
    const run = startBots({ url: MEMORY_URL, count: 2, seconds: 4, clock: h.clock, transport: net.transport, seed: 7, predict: nodePredictOptions({}, [ballGoals]) });
    let report: Awaited<typeof run.done> | null = null;
    void run.done.then((r) => (report = r));
    await h.settle(() => report !== null, 10_000);
    for (const b of report!.bots) {
      expect(b.prediction).toMatchObject({ mode: 'predict', desyncs: 0 });
      expect(b.prediction!.hashesVerified).toBeGreaterThan(3);
    }
  });

  it('rejects a bad bot count', () => {
    expect(() => startBots({ url: MEMORY_URL, count: 0 })).toThrow(/count/);
  });
});
