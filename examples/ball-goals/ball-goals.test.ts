// Ball Goals' own tests, on the public API only: the rules in a headless Simulation (a walk-and-kick scores, a goal
// resets the ball, the same inputs give the same hashes), then the game served for real: two SDK clients play over
// WebSocket, the score they see changes when the ball enters a goal, and the server's recording replays hash for hash.
import { mkdtempSync, readdirSync, rmSync } from 'node:fs';
import { tmpdir } from 'node:os';
import { join } from 'node:path';
import { fileURLToPath } from 'node:url';
import { afterAll, describe, expect, it } from 'vitest';
import { connect, type NetClient } from '../../api/client.ts';
import { createServer } from '../../api/index.ts';
import { NEUTRAL_INPUT, replayLog, Simulation, type SimEvent, type TickInputRecord } from '../../api/sim.ts';
import { KICK_OFF, scenario } from './game.ts';

const tmp = mkdtempSync(join(tmpdir(), 'ball-goals-'));
afterAll(() => rmSync(tmp, { recursive: true, force: true }));

type Score = { scoreRed: number; scoreBlue: number; lastGoal: string };

/** Player 1 (red, starting behind the ball facing −z) walks forward holding kick; player 2 stands still. */
function walkAndKick(ticks: number): TickInputRecord[] {
  const out: TickInputRecord[] = [{ tick: 0, leaves: [], joins: [{ playerId: 1, name: 'red' }, { playerId: 2, name: 'blue' }], commands: [] }];
  for (let t = 1; t < ticks; t++) out.push({ tick: t, leaves: [], joins: [], commands: [{ playerId: 1, input: { ...NEUTRAL_INPUT, moveZ: 127, game: [1] } }] });
  return out;
}

describe('ball-goals (simulation)', () => {
  it('scores for blue when red kicks the ball into red\'s own goal, then puts the ball back on the spot', async () => {
    const sim = await Simulation.create({ scenario });
    const ballId = sim.descriptors().find((d) => d.shape.kind === 'sphere')!.id;
    let goal: SimEvent | undefined;
    for (const r of walkAndKick(240)) {
      goal = sim.step(r).find((e) => e.type === 'scenario' && e.name === 'goal');
      if (goal) break;
    }
    expect(goal).toMatchObject({ value: 1 });
    expect(sim.gameState()).toEqual({ scoreRed: 0, scoreBlue: 1, lastGoal: 'blue' });
    const ball = sim.world.getBody(ballId)!;
    const at = ball.position();
    expect([at.x, at.y, at.z].map((v, i) => Math.abs(v - [KICK_OFF.x, KICK_OFF.y, KICK_OFF.z][i]))).toEqual([0, expect.any(Number), 0]);
    expect(Math.abs(at.y - KICK_OFF.y)).toBeLessThan(1e-6); // positions are float32
    expect(ball.linearVelocity()).toEqual({ x: 0, y: 0, z: 0 });
    sim.destroy();
  });

  it('does not move the ball for a kick out of reach', async () => {
    const sim = await Simulation.create({ scenario });
    sim.step({ tick: 0, leaves: [], joins: [{ playerId: 1, name: 'red' }], commands: [] });
    for (let t = 1; t < 30; t++) sim.step({ tick: t, leaves: [], joins: [], commands: [{ playerId: 1, input: { ...NEUTRAL_INPUT, game: [1] } }] });
    const ball = sim.world.getBody(sim.descriptors().find((d) => d.shape.kind === 'sphere')!.id)!.position();
    expect(Math.hypot(ball.x - KICK_OFF.x, ball.z - KICK_OFF.z)).toBeLessThan(0.01);
    sim.destroy();
  });

  it('gives the same hash every tick for the same inputs', async () => {
    const hashes = async (): Promise<string[]> => {
      const sim = await Simulation.create({ scenario });
      const out = walkAndKick(200).map((r) => (sim.step(r), sim.stateHash()));
      sim.destroy();
      return out;
    };
    expect(await hashes()).toEqual(await hashes());
  });
});

async function waitFor(what: string, done: () => boolean, timeoutMs = 20_000): Promise<void> {
  const until = Date.now() + timeoutMs;
  while (!done()) {
    if (Date.now() > until) throw new Error(`timed out waiting for ${what}`);
    await new Promise((r) => setTimeout(r, 10));
  }
}

describe.each([0, 1])('ball-goals (served, %i room workers)', (roomWorkers) => {
  it('lets two SDK clients play: a kick scores, both see the score, and the recording replays hash for hash', async () => {
    const recordDir = join(tmp, `rec-${roomWorkers}`);
    // Rooms in worker threads load the scenario from its module file; on the main thread the definition will do.
    const entry = roomWorkers > 0 ? fileURLToPath(new URL('./game.ts', import.meta.url)) : scenario;
    const server = await createServer({ scenarios: [entry], port: 0, host: '127.0.0.1', recordDir, recordHashEveryTicks: 1, roomWorkers, clientDir: join(tmp, 'no-page') });
    const clients: NetClient[] = [];
    try {
      for (const name of ['red', 'blue']) clients.push(connect(server.wsUrl, { name, reconnect: false }));
      await Promise.all(clients.map((c) => c.whenConnected()));
      const [red, blue] = clients;
      expect(red.welcome!.scenario.game?.input?.map((f) => f.name)).toEqual(['kick']);
      const scores: Score[] = [];
      blue.on('gameState', ({ state }) => scores.push(state as Score));
      await waitFor('the first state', () => scores.length > 0);
      expect(scores[0]).toEqual({ scoreRed: 0, scoreBlue: 0, lastGoal: '' });
      red.setInput({ ...NEUTRAL_INPUT, moveZ: 127, kick: 1 }); // the first player starts behind the ball, facing −z
      await waitFor('a goal', () => red.gameState<Score>().scoreBlue === 1 && blue.gameState<Score>().scoreBlue === 1);
      expect(blue.gameState<Score>()).toEqual({ scoreRed: 0, scoreBlue: 1, lastGoal: 'blue' });
      red.setInput(NEUTRAL_INPUT);
      red.sendMessage('resetBall');
    } finally {
      for (const c of clients) c.close();
      await server.close('test over');
    }
    const [file] = readdirSync(recordDir);
    const report = await replayLog(join(recordDir, file), { scenario });
    expect(report.status).toBe('ok');
    expect(report.hashesChecked).toBeGreaterThan(report.ticks);
  });
});
