// Browser test of the operators' monitor (GET /monitor) against a real server with an admin token: the page asks for
// the token, then lists a room and its two players live, and its "Close room" button ends both players' pages with
// the "Room closed" message.
import { afterAll, beforeAll, expect, it } from 'vitest';
import { buildClient } from '../../scripts/build-client.ts';
import { silentLogger } from '../../server/logger.ts';
import { createMetrics } from '../../server/metrics.ts';
import { startServer, type RunningServer } from '../../server/start-server.ts';
import { describeBrowser, launchBrowser, waitForHook, type BrowserSession } from '../helpers/browser.ts';

const TOKEN = 'browser-monitor-token-0123456789';

describeBrowser('monitor page', () => {
  let browser: BrowserSession;
  let server: RunningServer;

  beforeAll(async () => {
    const built = await buildClient();
    server = await startServer({ port: 0, scenario: 'shape-rain', params: { count: 4 }, clientDir: built.outDir, logger: silentLogger(), metrics: createMetrics({ processMetrics: false }), adminToken: TOKEN });
    const res = await fetch(new URL('/api/rooms', server.url), {
      method: 'POST',
      headers: { 'content-type': 'application/json', authorization: `Bearer ${TOKEN}` },
      body: JSON.stringify({ scenario: 'shape-rain', roomId: 'arena', params: { count: 3 } }),
    });
    if (!res.ok) throw new Error(`creating the room: ${res.status} ${await res.text()}`);
    browser = await launchBrowser();
  });

  afterAll(async () => {
    await browser?.close();
    await server?.close('test over');
  });

  it('lists a room and its two players live, closes it, and both pages say the room closed', async () => {
    const monitor = await browser.newPage();
    await monitor.page.goto(new URL('/monitor', server.url).href);
    await monitor.page.waitForSelector('#token-form:not([hidden])', { timeout: 15_000 });
    await expect(monitor.page.locator('#status').textContent()).resolves.toMatch(/admin token/);
    await monitor.page.fill('#token', TOKEN);
    await monitor.page.click('#token-form button');
    const room = monitor.page.locator('section.room[data-room="arena"]');
    await room.waitFor({ timeout: 15_000 });
    await expect(room.locator('tr[data-player]').count()).resolves.toBe(0);

    // Two players join; the monitor shows them without a reload.
    const ann = await browser.newPage();
    const bob = await browser.newPage();
    await ann.page.goto(new URL('/?room=arena&name=ann&hud=0', server.url).href);
    await bob.page.goto(new URL('/?room=arena&name=bob&hud=0', server.url).href);
    await waitForHook(ann.page, 't.connected');
    await waitForHook(bob.page, 't.connected');
    await monitor.page.waitForFunction(() => document.querySelectorAll('section.room[data-room="arena"] tr[data-player]').length === 2, null, { timeout: 15_000 });
    const names = await room.locator('tr[data-player] td:nth-child(2)').allTextContents();
    expect(names.sort()).toEqual(['ann', 'bob']);
    await expect(room.locator('h2 .scenario').textContent()).resolves.toBe('shape-rain');
    await expect(room.textContent()).resolves.toMatch(/count=3/);

    await room.locator('button[data-action="close"]').click();
    for (const p of [ann.page, bob.page]) {
      await waitForHook(p, "t.page === 'closed'", 15_000);
      await expect(p.locator('#message h2').textContent()).resolves.toBe('Room closed');
      await expect(p.locator('#message button').allTextContents()).resolves.toEqual(['Back to rooms']);
    }
    await monitor.page.waitForFunction(() => document.querySelector('section.room[data-room="arena"]') === null, null, { timeout: 15_000 });
    expect(monitor.errors.filter((e) => !/401/.test(e))).toEqual([]);
  });
});
