// Predicted play end to end in one process: two predicting clients of the client library and two scripted bots share
// a character-course room over an in-memory link with 50 ms each way, 10 ms jitter and 2% loss (retransmitted, as
// on TCP), on a manual clock. The predicting clients must never desync, must confirm the server's hashes and events,
// must show their own input on the next local tick, and the room's recording must replay. Where a walker stopped,
// every client's view comes to what the server confirmed.
import { mkdtempSync, readdirSync, rmSync } from 'node:fs';
import { tmpdir } from 'node:os';
import { join } from 'node:path';
import { afterAll, describe, expect, it } from 'vitest';
import { startBots } from '../../../cli/bots.ts';
import { nodePredictOptions } from '../../../cli/predict-options.ts';
import { replayLog } from '../../../cli/replay-session.ts';
import { scenario as characterCourse } from '../../../scenarios/character-course.ts';
import { scenario as shapeRain } from '../../../scenarios/shape-rain.ts';
import { connect, type NetClient } from '../../../sdk/index.ts';
import { Prng } from '../../../shared/sim/prng.ts';
import { commandYawRadians } from '../../../shared/sim/controls.ts';
import { Button, type InputCommand } from '../../../shared/sim/input.ts';
import type { SimEvent } from '../../../shared/sim/types.ts';
import { TICK_MS } from '../../../shared/tick-rate.ts';
import { MEMORY_URL, startHarness, type Harness } from '../../server/harness.ts';

const tmp = mkdtempSync(join(tmpdir(), 'taos-predict-'));
afterAll(() => rmSync(tmp, { recursive: true, force: true }));

/** Advances the manual clock in 4 ms steps for `ms`, letting promises (simulation start-up) settle between steps. */
async function play(h: Harness, ms: number, each?: (nowMs: number) => void): Promise<void> {
  for (let t = 0; t < ms; t += 4) {
    h.clock.advance(4);
    each?.(h.clock.nowMs());
    await new Promise((resolve) => setImmediate(resolve));
  }
}

function wander(rng: Prng): InputCommand {
  return { moveX: rng.int(-127, 127), moveZ: rng.int(0, 127), yaw: rng.int(0, 65535), pitch: 0, buttons: rng.next() < 0.2 ? 1 : 0 };
}

describe('predicted play', () => {
  it('keeps two predicting clients in step with the server under delay, jitter and loss', async () => {
    const recordDir = join(tmp, 'logs');
    // The manual clock outruns real disk syncs: records go out at once ('off'), the log is still written whole.
    const h = await startHarness({ scenarios: [characterCourse], recordDir, durability: { mode: 'off' }, resumeGraceMs: 0 });
    expect(h.room().netMode).toBe('predict');
    const rng = new Prng(5);
    const net = h.network({ latencyMs: 50, jitterMs: 10, lossRate: 0.02, random: () => rng.next() });
    const serverEvents: SimEvent[] = [];
    h.room().onTick((_record, events) => serverEvents.push(...events));
    const bots = startBots({ url: MEMORY_URL, count: 2, clock: h.clock, transport: net.transport, seed: 3, joinSpacingMs: 50 });
    const clients: NetClient[] = [];
    const events = new Map<NetClient, SimEvent[]>();
    for (const name of ['ann', 'bob']) {
      const c = connect(MEMORY_URL, { name, clock: h.clock, transport: net.transport, reconnect: false, predict: nodePredictOptions() });
      events.set(c, []);
      c.on('events', (e) => events.get(c)!.push(...e));
      clients.push(c);
    }
    const steer = [new Prng(11), new Prng(12)];
    let nextTurnMs = 0;
    await play(h, 12_000, (now) => {
      if (now < nextTurnMs) return;
      nextTurnMs = now + 150;
      clients.forEach((c, i) => c.setInput(wander(steer[i])));
    });

    // The own command shows on the next local tick.
    const ann = clients[0];
    const before = ann.predicted()!;
    const turn: InputCommand = { moveX: 0, moveZ: 127, yaw: 12345, pitch: 0, buttons: 0 };
    ann.setInput(turn);
    const pressedMs = h.clock.nowMs();
    let after = ann.predicted()!;
    for (let i = 0; i < 40 && after.tick === before.tick; i++) {
      h.clock.advance(1);
      after = ann.predicted()!;
      await new Promise((resolve) => setImmediate(resolve));
    }
    // The next tick the input loop fixes carries the command: at most one tick after the key. (Half a tick held only
    // at one phase of the link's random delays: with the key pressed 4 or 8 ms later the wait was 15 and 11 ms.)
    expect(h.clock.nowMs() - pressedMs).toBeLessThanOrEqual(Math.ceil(TICK_MS));
    expect(after.tick).toBeGreaterThan(before.tick);
    const own = after.characters.find((c) => c.playerId === ann.playerId)!;
    expect(own.yaw).toBeCloseTo(commandYawRadians(turn), 9);

    for (const c of clients) {
      const p = c.stats().prediction!;
      expect(p.mode).toBe('predict');
      expect(p.desyncs).toBe(0);
      // A hash every 30 ticks of the 12 s played, less the start (checkpoint, simulation start-up).
      expect(p.hashesVerified).toBeGreaterThan(15);
      expect(p.corrections).toBeGreaterThan(0);
      expect(p.rollbackDepthMax).toBeGreaterThan(3);
      // Events: the server's, from the join on (snapshot mode until the checkpoint, then derived from confirmed ticks).
      const mine = events.get(c)!;
      const from = c.welcome!.tick;
      const expected = serverEvents.filter((e) => e.tick >= from && e.tick < p.confirmedTick!);
      expect(mine.filter((e) => e.tick < p.confirmedTick!)).toEqual(expected);
      expect(expected.some((e) => e.type === 'bodySpawned')).toBe(true);
    }
    bots.stop();
    const report = await bots.done;
    expect(report.bots.every((b) => b.connected && b.snapshots > 100)).toBe(true);
    for (const c of clients) c.close();
    await play(h, 200);
    await h.close();
    const files = readdirSync(recordDir);
    expect(files).toHaveLength(1);
    const replay = await replayLog(join(recordDir, files[0]));
    expect(replay.status).toBe('ok');
    expect(replay.ticks).toBeGreaterThan(600);
  });

  it("brings every client's view of a walker that stopped to where the server has it", async () => {
    // A quiet room (one falling body): the walker is what moves. Sprinting, the walker covers ~12 cm a tick, so a
    // view that ran ahead with the last confirmed command overshoots by metres before the stop is confirmed.
    const h = await startHarness({ scenarios: [shapeRain], params: { count: 1 }, netMode: 'predict', durability: { mode: 'off' }, resumeGraceMs: 0 });
    const rng = new Prng(9);
    const net = h.network({ latencyMs: 50, jitterMs: 10, lossRate: 0.02, random: () => rng.next() });
    const clients = ['walker', 'watcher'].map((name) => connect(MEMORY_URL, { name, clock: h.clock, transport: net.transport, reconnect: false, predict: nodePredictOptions() }));
    const walker = clients[0];
    // Each client draws a frame every 16 ms (predicted() runs the frame's input step and returns what is drawn).
    let drawn: Array<{ x: number; z: number } | null> = [null, null];
    let lastFrameMs = 0;
    let startZ = 0;
    let watcherFurthest = 0;
    const frame = (now: number): void => {
      if (now - lastFrameMs < 16) return;
      lastFrameMs = now;
      drawn = clients.map((c) => c.predicted()?.characters.find((ch) => ch.playerId === walker.playerId)?.position ?? null);
      if (drawn[1]) watcherFurthest = Math.max(watcherFurthest, startZ - drawn[1].z);
    };
    await play(h, 2000, frame);
    const onServer = (): { x: number; z: number } => h.room().sim.characters().find((c) => c.playerId === walker.playerId)!.position;
    const start = onServer();
    startZ = start.z;
    walker.setInput({ moveX: 0, moveZ: 127, yaw: 0, pitch: 0, buttons: Button.Sprint });
    await play(h, 1500, frame);
    walker.setInput({ moveX: 0, moveZ: 0, yaw: 0, pitch: 0, buttons: 0 });
    // The server's walker stops; from then on, how long until each view shows it within 1 cm of there, and stays.
    let stoppedAtMs: number | null = null;
    let previous = onServer();
    const settledAtMs: Array<number | null> = [null, null];
    await play(h, 3000, (now) => {
      frame(now);
      const p = onServer();
      if (stoppedAtMs === null && p.z === previous.z) stoppedAtMs = now;
      previous = p;
      if (stoppedAtMs === null) return;
      drawn.forEach((d, i) => {
        const close = d !== null && Math.hypot(d.x - p.x, d.z - p.z) < 0.01;
        if (!close) settledAtMs[i] = null;
        else settledAtMs[i] ??= now;
      });
    });
    const end = onServer();
    expect(start.z - end.z).toBeGreaterThan(8);
    // The watcher drew the walk (and, running ahead on the last confirmed command, past where it stopped).
    expect(watcherFurthest).toBeGreaterThan(start.z - end.z);
    for (const [i, c] of clients.entries()) {
      const p = c.stats().prediction!;
      expect(p.mode).toBe('predict');
      expect(p.desyncs).toBe(0);
      expect(p.confirmedTick).toBeGreaterThan(h.room().sim.tick - 30);
      // Both views agree with the server to the millimetre, within 1.5 s of the server's walker stopping.
      expect(Math.hypot(drawn[i]!.x - end.x, drawn[i]!.z - end.z)).toBeLessThan(0.001);
      expect(settledAtMs[i]).not.toBeNull();
      expect(settledAtMs[i]! - stoppedAtMs!).toBeLessThan(1500);
    }
    for (const c of clients) c.close();
    await play(h, 200);
    await h.close();
  });
});
