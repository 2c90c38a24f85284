// Browser test of the client page against the real server (in-process, loopback port 0): the start screen lists the
// rooms and joins one, and WebGPU renders its falling bodies with no console errors.
import { afterAll, beforeAll, expect, it } from 'vitest';
import type { TaosState } from '../../client/app/test-hook.ts';
import type { RunningServer } from '../../server/start-server.ts';
import { buildClient } from '../../scripts/build-client.ts';
import {
  canvasPixels,
  createRoom,
  describeBrowser,
  dominantColor,
  fractionChanged,
  fractionUnlike,
  launchBrowser,
  readHook,
  startAppServer,
  waitForHook,
  type BrowserSession,
} from '../helpers/browser.ts';

describeBrowser('client page', () => {
  let browser: BrowserSession;
  let server: RunningServer;

  beforeAll(async () => {
    const built = await buildClient();
    server = await startAppServer({ scenario: 'character-course', clientDir: built.outDir });
    // A small endless rain: bodies are always falling somewhere.
    await createRoom(server.url, { scenario: 'shape-rain', roomId: 'rain', params: { count: 120, spawnPerTick: 1, recycleAfterTicks: 240 } });
    browser = await launchBrowser();
  });

  afterAll(async () => {
    await browser?.close();
    await server?.close('test over');
  });

  it('joins a room from the start screen and renders falling bodies on a WebGPU device without console errors', async () => {
    const { page, errors } = await browser.newPage();
    await page.goto(server.url);
    const rain = page.locator('#rooms li', { hasText: 'rain · shape-rain' });
    await rain.waitFor({ timeout: 15_000 });
    await expect(rain.locator('.desc').textContent()).resolves.toMatch(/rain onto a walled ground/);
    await rain.locator('button').click();
    await waitForHook(page, "t.connected && t.roomId === 'rain' && t.framesRendered >= 3 && t.bodies.length >= 10");
    const hook = await readHook<TaosState>(page);
    expect(hook.adapter?.architecture).toBeTruthy();
    expect(hook.scenario).toBe('shape-rain');
    expect(hook.playerId).toBeGreaterThan(0);

    // The rain comes in waves (spawns recycle after 240 ticks): wait for a moment with bodies high up.
    await waitForHook(page, 't.bodies.some((b) => b.position[1] > 2)', 15_000);
    const first = await canvasPixels(page);
    expect(fractionUnlike(first, dominantColor(first))).toBeGreaterThan(0.2);
    const falling = (await readHook<TaosState>(page)).bodies.filter((b) => b.position[1] > 2);
    expect(falling.length).toBeGreaterThan(0);
    await page.waitForTimeout(800);
    const second = await canvasPixels(page);
    expect(fractionChanged(first, second)).toBeGreaterThan(0.002);
    // The bodies that were high up have come down in the interpolated state.
    const later = new Map((await readHook<TaosState>(page)).bodies.map((b) => [b.id, b.position[1]]));
    const tracked = falling.filter((b) => later.has(b.id));
    expect(tracked.length).toBeGreaterThan(0);
    const fell = tracked.filter((b) => later.get(b.id)! < b.position[1] - 0.5);
    expect(fell.length).toBeGreaterThan(tracked.length / 2);
    expect(errors).toEqual([]);
    await page.close();
  });
});
