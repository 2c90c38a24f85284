// Browser test of a fleet (two servers in-process on loopback, one real redis-server, Chromium): the page served by B
// lists a room that A hosts, naming A, and joining it through B's page ends up in A's room (the page follows the
// room-moved bye).
import { afterAll, beforeAll, expect, it } from 'vitest';
import { silentLogger } from '../../server/logger.ts';
import { createMetrics } from '../../server/metrics.ts';
import { startServer, type RunningServer } from '../../server/start-server.ts';
import { buildClient } from '../../scripts/build-client.ts';
import { createRoom, describeBrowser, launchBrowser, readHook, waitForHook, type BrowserSession } from '../helpers/browser.ts';
import { describeRedis, startRedisServer, type RedisServer } from '../helpers/redis-server.ts';
import type { TaosState } from '../../client/app/test-hook.ts';

describeBrowser('a fleet in the page', () => {
  describeRedis('with Redis', () => {
    let browser: BrowserSession;
    let redis: RedisServer;
    const servers: RunningServer[] = [];

    beforeAll(async () => {
      const built = await buildClient();
      redis = await startRedisServer();
      for (let i = 0; i < 2; i++) {
        servers.push(
          await startServer({
            port: 0,
            host: '127.0.0.1',
            scenario: 'character-course',
            clientDir: built.outDir,
            logger: silentLogger(),
            metrics: createMetrics({ processMetrics: false }),
            fleet: { redisUrl: redis.url, ttlSeconds: 2 },
          }),
        );
      }
      browser = await launchBrowser();
    });

    afterAll(async () => {
      await browser?.close();
      for (const s of servers) await s.close('test over');
      await redis?.stop();
    });

    it("lists A's room on B's start screen and joins it there through A", async () => {
      const [a, b] = servers;
      await createRoom(a.url, { scenario: 'shape-rain', roomId: 'far', params: { count: 1 } });
      const { page, errors } = await browser.newPage();
      const aHost = new URL(a.url).host;
      // The lobby lists what B read from the directory: poll until A's room is there.
      for (let attempt = 0; ; attempt++) {
        await page.goto(b.url);
        const listed = await page.locator('#rooms').textContent({ timeout: 10_000 });
        if (listed?.includes('far · shape-rain')) {
          expect(listed).toContain(`on ${aHost}`);
          break;
        }
        if (attempt >= 20) throw new Error(`B's start screen never listed room far: ${listed}`);
        await new Promise((r) => setTimeout(r, 250));
      }
      await page.locator('button[data-room="far"]').click();
      await waitForHook(page, "t.connected && t.roomId === 'far'");
      const state = await readHook<TaosState>(page);
      expect(state.scenario).toBe('shape-rain');
      expect(new URL(page.url()).host).toBe(new URL(b.url).host);
      expect((await fetch(new URL('/api/rooms/far', a.url))).status).toBe(200);
      expect(((await (await fetch(new URL('/api/rooms/far', a.url))).json()) as { room: { clients: number } }).room.clients).toBe(1);
      expect(errors).toEqual([]);
    });
  });
});
