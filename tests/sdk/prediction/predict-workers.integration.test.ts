// Predicted play against the real server on loopback with the rooms in a worker thread: a predicting client of the
// client library over WebSocket gets its checkpoint and records from the worker, confirms the server's hashes and
// falls back to snapshots on request; a snapshot client in the same room still gets snapshots.
import { join } from 'node:path';
import { tmpdir } from 'node:os';
import { afterEach, describe, expect, it } from 'vitest';
import { nodePredictOptions } from '../../../cli/predict-options.ts';
import { connect, type NetClient } from '../../../sdk/index.ts';
import { silentLogger } from '../../../server/logger.ts';
import { createMetrics } from '../../../server/metrics.ts';
import { startServer, type RunningServer } from '../../../server/start-server.ts';

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

describe('predicted play with room workers', () => {
  it('predicts from a room in a worker over WebSocket and confirms its hashes', async () => {
    server = await startServer({ port: 0, roomWorkers: 1, scenario: 'character-course', logger: silentLogger(), metrics: createMetrics({ processMetrics: false }), clientDir: join(tmpdir(), 'taos-no-client') });
    expect(server.game.listRooms()[0]).toMatchObject({ id: 'default', netMode: 'predict' });
    const pred = connect(server.wsUrl, { name: 'pred', predict: nodePredictOptions(), reconnect: false });
    const snap = connect(server.wsUrl, { name: 'snap', reconnect: false });
    clients.push(pred, snap);
    await Promise.all([pred.whenConnected(), snap.whenConnected()]);
    const ownCharacter = () => pred.predicted()?.characters.find((c) => c.playerId === pred.playerId) ?? null;
    await waitUntil('the own character in the predicted world', 30_000, () => ownCharacter() !== null);
    const start = { ...ownCharacter()!.position };
    pred.setInput({ moveX: 0, moveZ: 127, yaw: 2000, pitch: 0, buttons: 0 });
    snap.setInput({ moveX: 50, moveZ: 100, yaw: 9000, pitch: 0, buttons: 2 });
    await waitUntil('three confirmed hashes', 30_000, () => (pred.stats().prediction?.hashesVerified ?? 0) >= 3);
    const p = pred.stats().prediction!;
    expect(p).toMatchObject({ mode: 'predict', desyncs: 0 });
    // The own walk shows in the predicted world: the character left its spawn (it may since have reached a wall, so
    // its distance from the start is checked, not its speed).
    const now = ownCharacter()!.position;
    expect(Math.hypot(now.x - start.x, now.z - start.z)).toBeGreaterThan(0.5);
    expect(snap.stats().snapshots).toBeGreaterThan(5);
    const snapshots = pred.stats().snapshots;
    pred.stopPredicting('test asks for snapshots');
    await waitUntil('snapshots after the fall back', 10_000, () => pred.stats().snapshots > snapshots + 5);
    expect(pred.stats().prediction).toMatchObject({ mode: 'snapshot', reason: 'test asks for snapshots' });
    expect(pred.predicted()).toBeNull();
  });
});
