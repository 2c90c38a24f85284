// Predicted play of a game on the game API (examples/ball-goals: a kick button, a replicated score, a resetBall
// message), in one process: the room picks predict mode on its own (auto), and two predicting clients of the client
// library play over an in-memory link with 50 ms each way, 10 ms jitter and 2% loss (retransmitted, as on TCP), on a
// manual clock. The clients' game input and messages reach the server's records; their score, goal events and state
// come from their own simulations and equal the server's on every confirmed tick; nobody desyncs; the own message
// shows on the next local tick; the recording replays.
import '../../../server/physics-node.ts';
import { mkdtempSync, readdirSync, rmSync } from 'node:fs';
import { tmpdir } from 'node:os';
import { join } from 'node:path';
import { afterAll, describe, expect, it } from 'vitest';
import { scenario as ballGoals, KICK_OFF } from '../../../examples/ball-goals/game.ts';
import { createSimulation } from '../../../cli/scenario-setup.ts';
import { replayLog } from '../../../cli/replay-session.ts';
import { connect, type NetClient, type PredictOptions } from '../../../sdk/index.ts';
import type { GameStateValues } from '../../../shared/sim/game-state.ts';
import { BODY_STATE_STRIDE } from '../../../shared/physics-data/body-state.ts';
import { NEUTRAL_INPUT } from '../../../shared/sim/input.ts';
import { Prng } from '../../../shared/sim/prng.ts';
import type { Simulation } from '../../../shared/sim/simulation.ts';
import type { SimEvent } from '../../../shared/sim/types.ts';
import { MEMORY_URL, startHarness, type Harness } from '../../server/harness.ts';

const tmp = mkdtempSync(join(tmpdir(), 'taos-predict-game-'));
afterAll(() => rmSync(tmp, { recursive: true, force: true }));

/** Advances the manual clock in 4 ms steps for `ms`, letting promises (simulation start-up) settle between steps. */
async function play(h: Harness, ms: number, each?: (nowMs: number) => void): Promise<void> {
  for (let t = 0; t < ms; t += 4) {
    h.clock.advance(4);
    each?.(h.clock.nowMs());
    await new Promise((resolve) => setImmediate(resolve));
  }
}

function predictBallGoals(smoothingHalfLifeMs?: number): PredictOptions {
  return { smoothingHalfLifeMs, createSimulation: (setup) => createSimulation(ballGoals, setup.params, setup.seed) };
}

/** The ball's position in a client's predicted frame. */
function ballAt(c: NetClient, ballId: number): { x: number; y: number; z: number } {
  const b = c.predicted()!.bodies;
  const i = Array.from(b.ids).indexOf(ballId);
  const at = i * BODY_STATE_STRIDE;
  return { x: b.states[at], y: b.states[at + 1], z: b.states[at + 2] };
}

describe('predicted play of a game-API scenario', () => {
  it('keeps two predicting ball-goals clients in step with the server: score, events, messages and hashes', async () => {
    const recordDir = join(tmp, 'logs');
    const h = await startHarness({ scenarios: [ballGoals], recordDir, durability: { mode: 'off' }, resumeGraceMs: 0 });
    const room = h.room();
    expect(room.netMode).toBe('predict');
    const sim = room.sim as Simulation;
    const serverState = new Map<number, GameStateValues>();
    const serverEvents: SimEvent[] = [];
    const messageTicks: number[] = [];
    room.onTick((record, events) => {
      serverState.set(record.tick, sim.gameState());
      serverEvents.push(...events);
      for (const _ of record.messages ?? []) messageTicks.push(record.tick);
    });
    const rng = new Prng(7);
    const net = h.network({ latencyMs: 50, jitterMs: 10, lossRate: 0.02, random: () => rng.next() });
    const events = new Map<NetClient, SimEvent[]>();
    const states = new Map<NetClient, GameStateValues[]>();
    const open = (name: string, smoothingHalfLifeMs?: number): NetClient => {
      const c = connect(MEMORY_URL, { name, clock: h.clock, transport: net.transport, reconnect: false, predict: predictBallGoals(smoothingHalfLifeMs) });
      events.set(c, []);
      states.set(c, []);
      c.on('events', (e) => events.get(c)!.push(...e));
      c.on('gameState', ({ state }) => states.get(c)!.push(state));
      return c;
    };
    // Red joins first (behind the ball, facing its own goal), drawn without smoothing so the test reads raw poses.
    const red = open('red', 0);
    await play(h, 400);
    const blue = open('blue');
    await play(h, 1_000);
    for (const c of [red, blue]) expect(c.stats().prediction?.mode).toBe('predict');

    // Red walks into the ball holding kick until it scores (for blue); blue wanders, kicking now and then.
    red.setInput({ ...NEUTRAL_INPUT, moveZ: 127, kick: 1 });
    const steer = new Prng(12);
    let nextTurnMs = 0;
    const wander = (now: number): void => {
      if (now < nextTurnMs) return;
      nextTurnMs = now + 150;
      blue.setInput({ ...NEUTRAL_INPUT, moveX: steer.int(-127, 127), moveZ: steer.int(-127, 127), yaw: steer.int(0, 65535), kick: steer.next() < 0.3 ? 1 : 0 });
    };
    type Score = { scoreRed: number; scoreBlue: number; lastGoal: string };
    for (let i = 0; i < 40 && red.gameState<Score>().lastGoal !== 'blue'; i++) await play(h, 250, wander);
    expect(red.gameState<Score>()).toMatchObject({ scoreBlue: 1, lastGoal: 'blue' });

    // The ball rolls away from the spot after a kick; red's resetBall puts it back on red's next local tick.
    const ballId = sim.descriptors().find((d) => d.shape.kind === 'sphere')!.id;
    red.setInput({ ...NEUTRAL_INPUT, moveZ: -127, kick: 1 });
    await play(h, 1_500, wander);
    red.setInput({ ...NEUTRAL_INPUT, yaw: 32768, moveZ: 127, kick: 1 });
    for (let i = 0; i < 20 && Math.hypot(ballAt(red, ballId).x - KICK_OFF.x, ballAt(red, ballId).z - KICK_OFF.z) < 1; i++) await play(h, 100, wander);
    const away = ballAt(red, ballId);
    expect(Math.hypot(away.x - KICK_OFF.x, away.z - KICK_OFF.z)).toBeGreaterThan(1);
    red.setInput(NEUTRAL_INPUT);
    const before = red.predicted()!.tick;
    red.sendMessage('resetBall');
    for (let i = 0; i < 40 && red.predicted()!.tick === before; i++) {
      h.clock.advance(1);
      await new Promise((resolve) => setImmediate(resolve));
    }
    const reset = ballAt(red, ballId);
    expect(Math.hypot(reset.x - KICK_OFF.x, reset.z - KICK_OFF.z)).toBeLessThan(0.05);
    await play(h, 3_000, wander);
    // The message asked for the tick red's simulation applied it on, and arrived in time for it.
    expect(messageTicks).toEqual([before]);

    for (const c of [red, blue]) {
      const p = c.stats().prediction!;
      expect(p.mode).toBe('predict');
      expect(p.desyncs).toBe(0);
      expect(p.hashesVerified).toBeGreaterThan(10);
      expect(p.corrections).toBeGreaterThan(0);
      // The state a client shows is the server's at its newest confirmed tick; every change it saw was the server's.
      expect(c.gameState()).toEqual(serverState.get(p.confirmedTick! - 1));
      const seen = states.get(c)!;
      expect(seen.length).toBeGreaterThan(1);
      const serverValues = [...serverState.values()].map((s) => JSON.stringify(s));
      for (const s of seen) expect(serverValues).toContain(JSON.stringify(s));
      // Goal events: the server's, from the join on, derived from the client's own confirmed ticks.
      const from = c.welcome!.tick;
      const goals = (list: SimEvent[]): SimEvent[] => list.filter((e) => e.type === 'scenario' && e.tick >= from && e.tick < p.confirmedTick!);
      expect(goals(events.get(c)!)).toEqual(goals(serverEvents));
      const score = c.gameState<Score>();
      expect(goals(serverEvents).length).toBeGreaterThanOrEqual(1);
      expect(score.scoreRed! + score.scoreBlue!).toBe(serverEvents.filter((e) => e.type === 'scenario' && e.tick < p.confirmedTick!).length);
    }
    for (const c of [red, blue]) c.close();
    await play(h, 200);
    await h.close();
    const files = readdirSync(recordDir);
    expect(files).toHaveLength(1);
    const replay = await replayLog(join(recordDir, files[0]), { scenario: ballGoals });
    expect(replay.status).toBe('ok');
    expect(replay.ticks).toBeGreaterThan(400);
  });
});
