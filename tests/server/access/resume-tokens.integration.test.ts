// Integration test of reconnect-with-resume on real loopback sockets: the client library's NetClient plays through
// a TCP relay that the test cuts (a dropped network, no close frame); the client reconnects by itself with its
// resume token and gets the same player and character back, the room records no leave or join for it, and the
// recording replays exactly.
import { mkdtempSync, readdirSync, rmSync } from 'node:fs';
import { createConnection, createServer, type Server, type Socket } from 'node:net';
import { tmpdir } from 'node:os';
import { join } from 'node:path';
import { afterAll, afterEach, describe, expect, it } from 'vitest';
import { connect, type NetClient } from '../../../sdk/client.ts';
import { replayLog } from '../../../cli/replay-session.ts';
import { silentLogger } from '../../../server/logger.ts';
import { createMetrics } from '../../../server/metrics.ts';
import { startServer, type RunningServer } from '../../../server/start-server.ts';
import type { WelcomeMessage } from '../../../shared/protocol/index.ts';
import { NEUTRAL_INPUT } from '../../../shared/sim/input.ts';
import type { SimEvent, TickInputRecord } from '../../../shared/sim/types.ts';

const tmp = mkdtempSync(join(tmpdir(), 'taos-resume-int-'));
afterAll(() => rmSync(tmp, { recursive: true, force: true }));
let server: RunningServer | null = null;
let relay: Relay | null = null;
const clients: NetClient[] = [];
afterEach(async () => {
  for (const c of clients.splice(0)) c.close();
  relay?.close();
  relay = null;
  await server?.close('test over');
  server = null;
});

/** A TCP relay in front of the server whose live connections can be cut at once (RST, no WebSocket close). */
interface Relay {
  port: number;
  cut(): void;
  close(): void;
}

async function startRelay(targetPort: number): Promise<Relay> {
  const pairs = new Set<[Socket, Socket]>();
  const listener: Server = createServer((inbound) => {
    const outbound = createConnection({ host: '127.0.0.1', port: targetPort });
    const pair: [Socket, Socket] = [inbound, outbound];
    pairs.add(pair);
    const end = (): void => {
      pairs.delete(pair);
      inbound.destroy();
      outbound.destroy();
    };
    for (const s of pair) {
      s.on('error', end);
      s.on('close', end);
    }
    inbound.pipe(outbound);
    outbound.pipe(inbound);
  });
  await new Promise<void>((resolve) => listener.listen(0, '127.0.0.1', resolve));
  const cut = (): void => {
    for (const [a, b] of [...pairs]) {
      a.resetAndDestroy();
      b.resetAndDestroy();
    }
    pairs.clear();
  };
  return {
    port: (listener.address() as { port: number }).port,
    cut,
    close() {
      cut();
      listener.close();
    },
  };
}

async function waitFor(what: string, cond: () => boolean, timeoutMs = 8000): Promise<void> {
  const end = performance.now() + timeoutMs;
  while (!cond()) {
    if (performance.now() > end) throw new Error(`timed out after ${timeoutMs} ms waiting for ${what}`);
    await new Promise((r) => setTimeout(r, 10));
  }
}

describe('resume over real sockets', () => {
  it('reconnects a client whose connection was cut with its resume token: same player and character, no leave or join, exact replay', async () => {
    const dir = join(tmp, 'rec');
    server = await startServer({ port: 0, scenario: 'character-course', recordDir: dir, logger: silentLogger(), metrics: createMetrics({ processMetrics: false }), clientDir: join(tmp, 'no-client') });
    const room = server.game.rooms.local('default')!;
    const records: TickInputRecord[] = [];
    room.onTick((r) => records.push(structuredClone(r)));
    relay = await startRelay(server.port);

    const ann = connect(`ws://127.0.0.1:${relay.port}/`, { name: 'ann', reconnect: { baseDelayMs: 50, maxDelayMs: 200 } });
    const bob = connect(server.wsUrl, { name: 'bob' });
    clients.push(ann, bob);
    const welcomes: WelcomeMessage[] = [];
    ann.on('welcome', (w) => welcomes.push(w));
    const bobEvents: SimEvent[] = [];
    bob.on('events', (e) => bobEvents.push(...e));
    const [first] = await Promise.all([ann.whenConnected(), bob.whenConnected()]);
    const annChar = () => room.sim.characters().find((c) => c.playerId === first.playerId);
    await waitFor('ann in the world', () => annChar() !== undefined);
    const bodyId = annChar()!.bodyId;
    ann.setInput({ ...NEUTRAL_INPUT, moveX: 127 });
    const start = { ...annChar()!.position };
    await waitFor('ann to walk 0.5 m', () => annChar()!.position.x - start.x > 0.5);

    relay.cut();
    await waitFor('ann to be welcomed again', () => welcomes.length === 2);
    expect(welcomes[1]).toMatchObject({ playerId: first.playerId, resumed: true, roomId: 'default' });
    expect(welcomes[1].resumeToken).not.toBe(first.resumeToken);
    expect(ann.stats().reconnects).toBe(1);
    expect(annChar()!.bodyId).toBe(bodyId);
    // Inputs flow again on the new connection: the character keeps walking.
    const resumedAt = annChar()!.position.x;
    await waitFor('ann to walk on after the reconnect', () => annChar()!.position.x - resumedAt > 0.5);

    const annJoinsLeaves = records.filter((r) => r.leaves.includes(first.playerId) || r.joins.some((j) => j.playerId === first.playerId));
    expect(annJoinsLeaves).toHaveLength(1); // the original join only
    expect(bobEvents.filter((e) => e.type === 'playerLeft')).toEqual([]);

    ann.close();
    bob.close();
    await server.close('test over');
    server = null;
    const report = await replayLog(join(dir, readdirSync(dir).filter((f) => f.endsWith('.taoslog'))[0]));
    expect(report.status).toBe('ok');
    expect(report.log).toBe('complete');
    expect(report.ticks).toBe(records.at(-1)!.tick + 1);
  });
});
