// Predicted play of a game on the game API (examples/ball-goals) against the real server on loopback, with the room in
// a worker thread: two predicting clients over WebSocket get checkpoints and records carrying game input and
// messages from the worker; the kick scores and both see the score from their own simulations, without a desync.
import { tmpdir } from 'node:os';
import { join } from 'node:path';
import { fileURLToPath } from 'node:url';
import { afterEach, describe, expect, it } from 'vitest';
import { createServer, type RunningServer } from '../../../api/index.ts';
import { createSimulation } from '../../../cli/scenario-setup.ts';
import { scenario as ballGoals } from '../../../examples/ball-goals/game.ts';
import { connect, type NetClient, type PredictOptions } from '../../../sdk/index.ts';
import { NEUTRAL_INPUT } from '../../../shared/sim/input.ts';

let server: RunningServer | null = null;
const clients: NetClient[] = [];
afterEach(async () => {
  for (const c of clients.splice(0)) c.close();
  await server?.close('test over');
  server = null;
});

async function waitUntil(what: string, timeoutMs: number, done: () => boolean): Promise<void> {
  const deadline = performance.now() + timeoutMs;
  while (!done()) {
    if (performance.now() > deadline) throw new Error(`timed out waiting for ${what}`);
    await new Promise((r) => setTimeout(r, 25));
  }
}

type Score = { scoreRed: number; scoreBlue: number; lastGoal: string };

describe('predicted play of a game-API room in a worker', () => {
  it('predicts ball-goals from a worker room: the kick scores, the score and messages agree with the server', async () => {
    // Rooms in worker threads load the scenario from its module file.
    const entry = fileURLToPath(new URL('../../../examples/ball-goals/game.ts', import.meta.url));
    server = await createServer({ scenarios: [entry], port: 0, host: '127.0.0.1', roomWorkers: 1, clientDir: join(tmpdir(), 'taos-no-client') });
    expect(server.game.listRooms()[0]).toMatchObject({ netMode: 'predict' });
    const predict: PredictOptions = { createSimulation: (s) => createSimulation(ballGoals, s.params, s.seed) };
    const red = connect(server.wsUrl, { name: 'red', predict, reconnect: false });
    clients.push(red);
    await red.whenConnected();
    const blue = connect(server.wsUrl, { name: 'blue', predict, reconnect: false });
    clients.push(blue);
    await blue.whenConnected();
    await waitUntil('both predicting', 30_000, () => red.stats().prediction?.mode === 'predict' && blue.stats().prediction?.mode === 'predict');
    red.setInput({ ...NEUTRAL_INPUT, moveZ: 127, kick: 1 }); // red starts behind the ball, facing its own goal
    await waitUntil('a goal seen by both', 60_000, () => red.gameState<Score>().scoreBlue === 1 && blue.gameState<Score>().scoreBlue === 1);
    red.setInput(NEUTRAL_INPUT);
    blue.sendMessage('resetBall');
    const verified = red.stats().prediction!.hashesVerified;
    await waitUntil('two more confirmed hashes', 30_000, () => [red, blue].every((c) => (c.stats().prediction?.hashesVerified ?? 0) >= verified + 2));
    for (const c of [red, blue]) {
      expect(c.stats().prediction).toMatchObject({ mode: 'predict', desyncs: 0 });
      expect(c.gameState()).toEqual({ scoreRed: 0, scoreBlue: 1, lastGoal: 'blue' });
    }
  });
});
