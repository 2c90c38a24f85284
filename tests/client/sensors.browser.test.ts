// Browser test of sensor events on screen (real server in-process on loopback port 0): walking into the
// character-course trigger zone lights its outline, the feed says the door opened, and the door slides away.
import { afterAll, beforeAll, expect, it } from 'vitest';
import type { TaosState } from '../../client/app/test-hook.ts';
import type { RunningServer } from '../../server/start-server.ts';
import { buildClient } from '../../scripts/build-client.ts';
import { canvasPixels, countPixels, describeBrowser, launchBrowser, readHook, startAppServer, waitForHook, waitUntilStill, type BrowserSession } from '../helpers/browser.ts';

/** A lit trigger outline: bright yellow (the idle outline is drawn at 40 % of its colour and fails this). */
const litYellow = (r: number, g: number, b: number): boolean => r > 230 && g > 215 && b < 150;

describeBrowser('sensor events on the page', () => {
  let browser: BrowserSession;
  let server: RunningServer;

  beforeAll(async () => {
    const built = await buildClient();
    // Snapshot play: the zone lights when the server's event arrives, close behind the drawn character. (In predicted
    // play events come from confirmed ticks, which trail the drawn world by the confirmation delay.)
    server = await startAppServer({ scenario: 'character-course', clientDir: built.outDir, netMode: 'snapshot' });
    browser = await launchBrowser();
  });

  afterAll(async () => {
    await browser?.close();
    await server?.close('test over');
  });

  it('lights the trigger zone and opens the door when the player walks in', async () => {
    const { page, errors } = await browser.newPage();
    await page.goto(new URL('/?room=&name=runner&hud=0', server.url).href);
    await waitForHook(page, 't.connected && t.characters.length === 1 && t.framesRendered >= 3');
    const start = await readHook<TaosState>(page);
    expect(start.sensors.length).toBeGreaterThan(0);
    expect(start.sensors.every((s) => !s.occupied && !s.lit)).toBe(true);
    // The sliding door: the kinematic body standing in the doorway of the wall at x = 14.
    const door = start.bodies.find((b) => Math.abs(b.position[0] - 14) < 0.01 && Math.abs(b.position[2] - 10) < 0.01);
    expect(door).toBeDefined();
    // Yellow props may be in view already; the lit outline adds a lot more bright yellow.
    const yellowBefore = countPixels(await canvasPixels(page, 'canvas#scene', 320), litYellow);

    // D strafes right (+X at the initial yaw) towards the doorway, at walking speed: the zone is 6 m deep, so the
    // character stops inside it even though it keeps going for the input lead and interpolation delay after the key.
    await page.keyboard.down('KeyD');
    await waitForHook(page, 't.error !== null || t.sensors.some((s) => s.occupied)', 20_000);
    await page.keyboard.up('KeyD');
    await waitUntilStill(page, start.playerId!);
    await waitForHook(page, `t.events.includes('door opened') && t.bodies.some((b) => b.id === ${door!.id} && b.position[2] < ${door!.position[2] - 1})`, 15_000);

    const inside = await readHook<TaosState>(page);
    expect(inside.error).toBeNull();
    const zone = inside.sensors.find((s) => s.occupied)!;
    expect(zone.lit).toBe(true);
    expect(inside.events.some((line) => line === `player #${inside.playerId} entered zone ${zone.sensorId}`)).toBe(true);
    // The lit outline is on screen around the player.
    const yellowAfter = countPixels(await canvasPixels(page, 'canvas#scene', 320), litYellow);
    expect(yellowAfter).toBeGreaterThan(yellowBefore + 200);
    expect(errors).toEqual([]);
    await page.close();
  });
});
