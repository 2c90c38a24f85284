// A `serve --redis` process while its Redis is missing or stalled: it starts and serves without Redis, joins the fleet
// once Redis comes up, and a Redis that stops answering (DEBUG SLEEP) holds up neither the room list nor a room.
import { Redis } from 'ioredis';
import { afterEach, expect, it } from 'vitest';
import { describeRedis, freePort, startRedisServer, type RedisServer } from '../../helpers/redis-server.ts';
import { startServeProcess, type ServeProcess } from '../../helpers/serve-process.ts';
import { WsTestClient } from '../ws-client.ts';

const started: Array<{ stop(): Promise<void> }> = [];
afterEach(async () => {
  for (const s of started.splice(0).reverse()) await s.stop();
});

async function serve(redisUrl: string): Promise<ServeProcess> {
  const proc = await startServeProcess(['--redis', redisUrl, '--fleet-ttl', '2', '--log-level', 'warn', '--client-dir', '/nonexistent']);
  started.push({ stop: () => proc.stop('SIGKILL') });
  return proc;
}

async function redis(opts: Parameters<typeof startRedisServer>[0] = {}): Promise<RedisServer> {
  const r = await startRedisServer(opts);
  started.push(r);
  return r;
}

async function eventually(pred: () => Promise<boolean>, timeoutMs: number, what: string): Promise<void> {
  const start = performance.now();
  while (!(await pred())) {
    if (performance.now() - start > timeoutMs) throw new Error(`timed out after ${timeoutMs} ms waiting until ${what}`);
    await new Promise((r) => setTimeout(r, 100));
  }
}

const create = (s: ServeProcess, roomId: string): Promise<Response> => fetch(`${s.url}api/rooms`, { method: 'POST', body: JSON.stringify({ scenario: 'character-course', roomId }) });

describeRedis('a fleet member without a working Redis', () => {
  it('starts and serves without Redis, refuses new room ids clearly, and joins the fleet once Redis comes up', async () => {
    const port = await freePort();
    const proc = await serve(`redis://127.0.0.1:${port}`);
    const health = await fetch(`${proc.url}healthz`);
    expect(health.status).toBe(200);
    expect(await health.json()).toMatchObject({ ok: true, fleet: { url: proc.url, redis: 'unreachable' } });
    const player = await WsTestClient.join(proc.wsUrl, 'Ada');
    expect(player.welcome?.roomId).toBe('default');
    player.close();
    const refused = await create(proc, 'later');
    expect(refused.status).toBe(503);
    expect(await refused.json()).toEqual({ error: 'server-full', message: expect.stringContaining('fleet directory does not answer') });
    expect(proc.log()).toContain('serving local rooms, retrying');

    const r = await redis({ port });
    await eventually(async () => (await create(proc, 'later')).status === 201, 15_000, 'the room id can be claimed');
    await eventually(async () => ((await (await fetch(`${proc.url}healthz`)).json()) as { fleet: { redis: string } }).fleet.redis === 'connected', 5000, '/healthz says Redis is connected');
    const client = new Redis(r.url);
    try {
      const owner = await client.get('taos:room:later');
      expect(await client.smembers('taos:members')).toEqual([owner]);
    } finally {
      client.disconnect();
    }
  });

  it('answers the room list and keeps its rooms ticking while Redis stalls', async () => {
    const r = await redis({ debugCommand: true });
    const proc = await serve(r.url);
    const player = await WsTestClient.join(proc.wsUrl, 'Bo');
    const client = new Redis(r.url);
    try {
      let stallOver = false;
      const stall = client.call('DEBUG', 'SLEEP', '6').then(() => (stallOver = true));
      await new Promise((resolve) => setTimeout(resolve, 200));
      const framesBefore = player.frames.length;
      const res = await fetch(`${proc.url}api/rooms`);
      expect(res.status).toBe(200);
      expect(((await res.json()) as { rooms: Array<{ id: string }> }).rooms.map((room) => room.id)).toEqual(['default']);
      await player.waitFor(() => player.frames.length >= framesBefore + 10, 4000, 'snapshots during the stall');
      expect(stallOver).toBe(false);
      await stall;
    } finally {
      player.close();
      client.disconnect();
    }
  });
});
