// Browser test of predicted play against the real server: a page in a predict room loads the physics chunk and
// Jolt's .wasm, runs the room's simulation itself (HUD: mode, input delay, rollback, re-sim, corrections, desyncs)
// and draws its own move in a world it simulated ahead of what the server has confirmed; a page in a snapshot room
// loads no Jolt byte and draws the move in the server's past (interpolated snapshots).
import type { Page } from 'playwright-core';
import { afterAll, beforeAll, expect, it } from 'vitest';
import type { TaosState } from '../../client/app/test-hook.ts';
import type { RunningServer } from '../../server/start-server.ts';
import { buildClient } from '../../scripts/build-client.ts';
import { createRoom, describeBrowser, launchBrowser, readHook, startAppServer, waitForHook, waitUntilStill, type BrowserSession } from '../helpers/browser.ts';

/** Requests for the physics chunk or Jolt's .wasm. */
const JOLT_REQUEST = /\/chunks\/(physics-[^/]+\.js|jolt-physics[^/]*\.(js|wasm))$/;

/** Opens a room's page, collecting the URLs it requests; resolves once its own character is drawn. */
async function openRoom(browser: BrowserSession, server: RunningServer, room: string): Promise<{ page: Page; errors: string[]; requests: string[]; me: number }> {
  const { page, errors } = await browser.newPage();
  const requests: string[] = [];
  page.on('request', (r) => requests.push(new URL(r.url()).pathname));
  await page.goto(new URL(`/?room=${room}&name=walker`, server.url).href);
  await waitForHook(page, 't.connected && t.characters.some((c) => c.playerId === t.playerId) && t.framesRendered >= 3', 30_000);
  return { page, errors, requests, me: (await readHook<TaosState>(page)).playerId! };
}

/** Holds a move key from standing still until the page has measured key → motion; returns the measurement. */
async function walk(page: Page, me: number, key = 'KeyW'): Promise<NonNullable<TaosState['keyToMotion']>> {
  await waitUntilStill(page, me);
  const count = (await readHook<TaosState>(page)).keyToMotion?.count ?? 0;
  await page.keyboard.down(key);
  await waitForHook(page, `t.keyToMotion !== null && t.keyToMotion.count > ${count}`, 20_000);
  await page.keyboard.up(key);
  return (await readHook<TaosState>(page)).keyToMotion!;
}

/**
 * Waits until the page's prediction has room to run ahead (the present less than 50 ticks past the confirmed tick, of
 * the 60 allowed): with the window full, the page waits for the server before it simulates anything new. On a
 * loaded machine the gap is the round trip plus the input lead, both measured long there (58 ticks seen at load 18).
 */
async function predictionHasRoom(page: Page): Promise<void> {
  await waitForHook(page, 't.net.prediction !== null && t.net.prediction.presentTick - t.net.prediction.confirmedTick < 50', 20_000);
}

describeBrowser('predicted play', () => {
  let browser: BrowserSession;
  let server: RunningServer;

  beforeAll(async () => {
    const built = await buildClient();
    server = await startAppServer({ scenario: 'character-course', clientDir: built.outDir });
    // Quiet rooms (one falling body) of the same scene, one in each net mode.
    await createRoom(server.url, { scenario: 'shape-rain', roomId: 'predicted', params: { count: 1 }, netMode: 'predict' });
    await createRoom(server.url, { scenario: 'shape-rain', roomId: 'snapshots', params: { count: 1 }, netMode: 'snapshot' });
    browser = await launchBrowser();
  });

  afterAll(async () => {
    await browser?.close();
    await server?.close('test over');
  });

  it('draws the own move in a world it simulates ahead of the server, having loaded the physics chunk', async () => {
    const { page, errors, requests, me } = await openRoom(browser, server, 'predicted');
    await waitForHook(page, "t.net.prediction !== null && t.net.prediction.mode === 'predict'");
    expect((await readHook<TaosState>(page)).net.netMode).toBe('predict');
    expect(requests.filter((r) => JOLT_REQUEST.test(r)).length).toBeGreaterThanOrEqual(2);
    expect(requests.some((r) => r.endsWith('.wasm'))).toBe(true);

    // The move is drawn in a world the page simulated ahead of everything the server had confirmed: no round trip.
    // Every key shows on the first frame drawn after it: that frame samples the key and simulates its tick at once.
    for (const key of ['KeyW', 'KeyS', 'KeyD', 'KeyA']) {
      await predictionHasRoom(page);
      const moved = await walk(page, me, key);
      expect(moved.shownAfterTicks).toBeGreaterThan(moved.keyTick);
      expect(moved.shownAheadOfServerTicks).toBeGreaterThan(0);
      expect({ key, frames: moved.frames, staleFrames: moved.staleFrames }).toEqual({ key, frames: 1, staleFrames: 0 });
    }

    // The HUD shows predicted play's numbers; the server's hashes have been checked and matched.
    await waitForHook(page, 't.net.prediction.hashesVerified >= 2');
    const hook = await readHook<TaosState>(page);
    expect(hook.net.prediction?.desyncs).toBe(0);
    expect(hook.net.prediction?.inputDelayTicks).toBe(0);
    await expect(page.locator('#hud [data-field="netMode"]').textContent()).resolves.toBe('predict');
    await expect(page.locator('#hud [data-field="desyncs"]').textContent()).resolves.toBe('0');
    await expect(page.locator('#hud [data-field="rollback"]').textContent()).resolves.toMatch(/^\d+ ticks \(p99 \d+\)$/);
    await expect(page.locator('#hud [data-field="resim"]').textContent()).resolves.toMatch(/^\d+\.\d\d ms \(p99 \d+\.\d\d\)$/);
    expect(await page.locator('#hud [data-field="interpolationDelayMs"]').isVisible()).toBe(false);
    expect(errors).toEqual([]);
    await page.close();
  }, 120_000);

  it('loads no Jolt byte in a snapshot room, where the move shows in a world behind the server', async () => {
    const { page, errors, requests, me } = await openRoom(browser, server, 'snapshots');
    const hook = await readHook<TaosState>(page);
    expect(hook.net.netMode).toBe('snapshot');
    expect(hook.net.prediction).toBeNull();
    const moved = await walk(page, me);
    // Snapshot play draws the server's past: the move shows in a world behind the server's tick.
    expect(moved.shownAheadOfServerTicks).toBeLessThan(0);
    expect(requests.filter((r) => JOLT_REQUEST.test(r))).toEqual([]);
    await expect(page.locator('#hud [data-field="netMode"]').textContent()).resolves.toBe('snapshot');
    expect(await page.locator('#hud [data-field="rollback"]').isVisible()).toBe(false);
    expect(errors).toEqual([]);
    await page.close();
  });
});
