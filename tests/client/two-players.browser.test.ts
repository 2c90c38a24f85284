// Browser test of two players in one room (real server in-process on loopback port 0, two Chromium processes): keys
// pressed in one page move its character, and the other page's interpolated state and pixels show it moving; in a
// predict room both pages' own simulations bring the walker to where the server has it stop.
import { afterAll, beforeAll, expect, it } from 'vitest';
import type { TaosState } from '../../client/app/test-hook.ts';
import type { RunningServer } from '../../server/start-server.ts';
import { buildClient } from '../../scripts/build-client.ts';
import {
  canvasPixels,
  createRoom,
  describeBrowser,
  distance3,
  launchBrowser,
  projectToCanvas,
  readHook,
  regionChanged,
  startAppServer,
  waitForHook,
  waitUntilStill,
  type BrowserSession,
  type HookCamera,
} from '../helpers/browser.ts';

/** Height of a character capsule's middle above its feet (m): where to look for it on screen. */
const CAPSULE_MID_METRES = 0.9;

describeBrowser('two players', () => {
  let browser: BrowserSession;
  let server: RunningServer;

  beforeAll(async () => {
    const built = await buildClient();
    server = await startAppServer({ scenario: 'character-course', clientDir: built.outDir });
    // A quiet room (a single falling body) so that what moves on screen is the other player. A snapshot room: this
    // test is about the interpolated view of another player (tests/client/predicted-play.browser.test.ts covers
    // predict rooms).
    await createRoom(server.url, { scenario: 'shape-rain', roomId: 'duo', params: { count: 1 }, netMode: 'snapshot' });
    browser = await launchBrowser();
  });

  afterAll(async () => {
    await browser?.close();
    await server?.close('test over');
  });

  it("shows one page's character moving on the other page when its keys are pressed", async () => {
    // A second browser: a background tab would stop drawing (no animation frames for hidden pages).
    const other = await launchBrowser();
    const a = await browser.newPage();
    const b = await other.newPage();
    // The watcher joins first (the leftmost spawn slot), so the walker spawns to its right: in view over the
    // watcher's right shoulder, not behind the watcher's own capsule.
    await b.page.goto(new URL('/?room=duo&name=watcher&hud=0', server.url).href);
    await waitForHook(b.page, "t.connected && t.characters.some((c) => c.playerId === t.playerId)");
    await a.page.goto(new URL('/?room=duo&name=walker&hud=0', server.url).href);
    await waitForHook(a.page, "t.connected && t.characters.some((c) => c.playerId === t.playerId)");
    await waitForHook(b.page, 't.characters.length >= 2 && t.framesRendered >= 3');
    const walkerId = (await readHook<TaosState>(a.page)).playerId!;
    const before = await readHook<TaosState>(b.page);
    const startOnB = before.characters.find((c) => c.playerId === walkerId)!.position;
    const startOnA = (await readHook<TaosState>(a.page)).characters.find((c) => c.playerId === walkerId)!.position;
    const pixelsBefore = await canvasPixels(b.page, 'canvas#scene', 320);
    const cameraBefore = (await readHook<TaosState>(b.page)).camera as HookCamera;

    // W walks forward (−Z at the initial yaw); shift sprints.
    await a.page.keyboard.down('ShiftLeft');
    await a.page.keyboard.down('KeyW');
    await waitForHook(a.page, `t.error !== null || t.characters.some((c) => c.playerId === ${walkerId} && c.position[2] < ${startOnA[2] - 2.5})`, 20_000);
    await a.page.keyboard.up('KeyW');
    await a.page.keyboard.up('ShiftLeft');

    // Let the walker stop on both screens (B draws it ~100–200 ms late) before comparing.
    await waitUntilStill(a.page, walkerId);
    await waitUntilStill(b.page, walkerId);
    const hookA = await readHook<TaosState>(a.page);
    expect(hookA.error).toBeNull();
    const onA = hookA.characters.find((c) => c.playerId === walkerId)!.position;
    expect(startOnA[2] - onA[2]).toBeGreaterThan(2.5);
    expect(Math.abs(onA[0] - startOnA[0])).toBeLessThan(0.5);
    const after = await readHook<TaosState>(b.page);
    const endOnB = after.characters.find((c) => c.playerId === walkerId)!.position;
    expect(startOnB[2] - endOnB[2]).toBeGreaterThan(2.5);
    // Both pages agree where the walker stopped.
    expect(distance3(endOnB, onA)).toBeLessThan(0.05);
    // The watcher did not move, so its camera did not either: what changed on screen is the walker.
    const watcherId = after.playerId!;
    const watcherMoved = distance3(after.characters.find((c) => c.playerId === watcherId)!.position, before.characters.find((c) => c.playerId === watcherId)!.position);
    expect(watcherMoved).toBeLessThan(0.1);
    const cameraAfter = after.camera as HookCamera;
    expect(distance3(cameraAfter.eye, cameraBefore.eye)).toBeLessThan(0.1);
    const pixelsAfter = await canvasPixels(b.page, 'canvas#scene', 320);
    // Where the walker stands now (it started beside the watcher, out of its view), its capsule appeared.
    const to = projectToCanvas(cameraAfter, [endOnB[0], endOnB[1] + CAPSULE_MID_METRES, endOnB[2]]);
    expect(to).not.toBeNull();
    expect(to!.x).toBeGreaterThan(0.05);
    expect(to!.x).toBeLessThan(0.95);
    expect(regionChanged(pixelsBefore, pixelsAfter, to!.x, to!.y, 1)).toBeGreaterThan(0.5);
    // A control spot of sky, away from both characters, did not change.
    expect(regionChanged(pixelsBefore, pixelsAfter, 0.9, 0.1, 2)).toBe(0);
    expect(a.errors).toEqual([]);
    expect(b.errors).toEqual([]);
    await a.page.close();
    await other.close();
  });

  it('brings both pages of a predict room to where the server has the walker stop', async () => {
    // Opened here: an empty room closes after its grace period, which the test before this one outlasts.
    await createRoom(server.url, { scenario: 'shape-rain', roomId: 'duo-predicted', params: { count: 1 }, netMode: 'predict' });
    const other = await launchBrowser();
    const a = await browser.newPage();
    const b = await other.newPage();
    const predicting = "t.connected && t.net.prediction !== null && t.net.prediction.mode === 'predict' && t.characters.some((c) => c.playerId === t.playerId)";
    await b.page.goto(new URL('/?room=duo-predicted&name=watcher&hud=0', server.url).href);
    await waitForHook(b.page, predicting);
    await a.page.goto(new URL('/?room=duo-predicted&name=walker&hud=0', server.url).href);
    await waitForHook(a.page, predicting);
    await waitForHook(b.page, 't.characters.length >= 2 && t.framesRendered >= 3');
    const walkerId = (await readHook<TaosState>(a.page)).playerId!;
    const room = server.game.rooms.local('duo-predicted')!;
    const onServer = (): number[] => {
      const p = room.sim.characters().find((c) => c.playerId === walkerId)!.position;
      return [p.x, p.y, p.z];
    };
    const start = onServer();

    await a.page.keyboard.down('ShiftLeft');
    await a.page.keyboard.down('KeyW');
    await waitForHook(a.page, `t.error !== null || t.characters.some((c) => c.playerId === ${walkerId} && c.position[2] < ${start[2] - 2.5})`, 20_000);
    await a.page.keyboard.up('KeyW');
    await a.page.keyboard.up('ShiftLeft');

    // The page runs ahead of the server by its input lead (more on a loaded machine): first the server's walker walks
    // the same way, then it stops (two reads 250 ms apart agree); that is where it stands, at that tick.
    for (let i = 0; i < 80 && start[2] - onServer()[2] <= 2.5; i++) await a.page.waitForTimeout(250);
    let end = onServer();
    for (let i = 0; i < 60; i++) {
      await a.page.waitForTimeout(250);
      const now = onServer();
      const still = distance3(now, end) === 0;
      end = now;
      if (still) break;
    }
    const stoppedTick = room.sim.tick;
    expect(start[2] - end[2]).toBeGreaterThan(2.5);
    // Each page's drawn walker comes to within 1 cm of there once the page has confirmed that tick: a page drawing
    // the walker still somewhere else (or an overshoot that never glides back) fails here.
    for (const { page } of [a, b]) {
      await waitForHook(
        page,
        `t.net.prediction !== null && t.net.prediction.confirmedTick > ${stoppedTick} && t.characters.some((c) => c.playerId === ${walkerId} && Math.hypot(c.position[0] - ${end[0]}, c.position[1] - ${end[1]}, c.position[2] - ${end[2]}) < 0.01)`,
        15_000,
      );
    }
    const onA = (await readHook<TaosState>(a.page)).characters.find((c) => c.playerId === walkerId)!.position;
    const onB = (await readHook<TaosState>(b.page)).characters.find((c) => c.playerId === walkerId)!.position;
    expect(distance3(onA, onB)).toBeLessThan(0.02);
    for (const { page } of [a, b]) expect((await readHook<TaosState>(page)).net.prediction?.desyncs).toBe(0);
    expect(a.errors).toEqual([]);
    expect(b.errors).toEqual([]);
    await a.page.close();
    await other.close();
  }, 120_000);
});
