// Browser test of the page's key → own motion meter (client/app/motion-meter.ts) in a snapshot room against the real
// server: W pressed while the own character stands still is measured to the first drawn frame that shows it walking,
// which in snapshot mode draws a world the server had run past the key's first input tick.
import { afterAll, beforeAll, expect, it } from 'vitest';
import type { TaosState } from '../../client/app/test-hook.ts';
import type { RunningServer } from '../../server/start-server.ts';
import { buildClient } from '../../scripts/build-client.ts';
import { createRoom, describeBrowser, launchBrowser, readHook, startAppServer, waitForHook, waitUntilStill, type BrowserSession } from '../helpers/browser.ts';

describeBrowser('key to motion', () => {
  let browser: BrowserSession;
  let server: RunningServer;

  beforeAll(async () => {
    const built = await buildClient();
    server = await startAppServer({ scenario: 'character-course', clientDir: built.outDir });
    await createRoom(server.url, { scenario: 'shape-rain', roomId: 'walk', params: { count: 1 } });
    browser = await launchBrowser();
  });

  afterAll(async () => {
    await browser?.close();
    await server?.close('test over');
  });

  it("measures W to the first frame that draws the own character walking, a world past the key's input tick", async () => {
    const { page, errors } = await browser.newPage();
    await page.goto(new URL('/?room=walk&name=walker&hud=0', server.url).href);
    await waitForHook(page, 't.connected && t.characters.some((c) => c.playerId === t.playerId) && t.framesRendered >= 3');
    const me = (await readHook<TaosState>(page)).playerId!;
    await waitUntilStill(page, me);
    expect((await readHook<TaosState>(page)).keyToMotion).toBeNull();
    await page.keyboard.down('KeyW');
    await waitForHook(page, 't.keyToMotion !== null', 20_000);
    await page.keyboard.up('KeyW');
    const hook = await readHook<TaosState>(page);
    const measured = hook.keyToMotion!;
    expect(measured.count).toBe(1);
    expect(measured.frames).toBeGreaterThanOrEqual(1);
    expect(measured.ms).toBeGreaterThan(0);
    // The move comes back in a snapshot of a tick the server ran with the key's command, drawn behind the delay.
    expect(measured.shownAfterTicks).toBeGreaterThan(measured.keyTick);
    expect(hook.net.interpolationDelayMs).toBeGreaterThan(0);
    expect(errors).toEqual([]);
    await page.close();
  });
});
