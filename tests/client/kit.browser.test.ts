// Browser test of the kit (/kit.js, client/kit/) as `init`'s page uses it: a game's own page, served with --page
// beside the built client, joins the game's scenario, draws the room, and walks the player's character on W.
import { mkdir, mkdtemp, rm, writeFile } from 'node:fs/promises';
import { tmpdir } from 'node:os';
import { join } from 'node:path';
import { afterAll, beforeAll, expect, it } from 'vitest';
import { scaffoldFiles } from '../../cli/scaffold-files.ts';
import { buildClient } from '../../scripts/build-client.ts';
import { scenarioSource } from '../../server/create-server.ts';
import { silentLogger } from '../../server/logger.ts';
import { loadScenarioModule } from '../../server/scenario-module.ts';
import { startServer, type RunningServer } from '../../server/start-server.ts';
import type { PlayHandle } from '../../client/kit/play.ts';
import { canvasPixels, describeBrowser, dominantColor, fractionUnlike, launchBrowser, type BrowserSession } from '../helpers/browser.ts';
import { writeGameModule } from '../helpers/game-module.ts';

describeBrowser('kit', () => {
  let dir = '';
  let browser: BrowserSession;
  let server: RunningServer;

  beforeAll(async () => {
    dir = await mkdtemp(join(tmpdir(), 'taos-kit-'));
    const built = await buildClient({ outDir: join(dir, 'client') });
    await mkdir(join(dir, 'page'));
    // init's page, with the game handle tapped for the test (the page keeps it in its module scope).
    const html = scaffoldFiles({ name: 'crate-drop', dependency: '*' })['page/index.html'];
    if (!html.includes('const game = await play(')) throw new Error("init's page no longer calls play() as this test expects");
    await writeFile(join(dir, 'page', 'index.html'), html.replace('const game = await play(', 'const game = window.game = await play('));
    const def = await loadScenarioModule(await writeGameModule(dir));
    // One crate: once it has landed, what moves on screen is the player.
    server = await startServer({ port: 0, scenarios: scenarioSource([def]), scenario: def.name, params: { crates: 1 }, clientDir: built.outDir, pageDir: join(dir, 'page'), logger: silentLogger() });
    browser = await launchBrowser();
  });

  afterAll(async () => {
    await browser?.close();
    await server?.close('test over');
    await rm(dir, { recursive: true, force: true });
  });

  it("draws the game's room on its own page and walks the player's character when W is held", async () => {
    const { page, errors } = await browser.newPage();
    await page.goto(server.url);
    await page.waitForFunction(() => document.getElementById('score')?.textContent?.startsWith('goals: 0'), null, { timeout: 30_000 });
    // The character as the page's connection sees it (interpolated snapshots), once it is there.
    const mine = (): Promise<number[] | null> =>
      page.evaluate(() => {
        const client = (window as unknown as { game: PlayHandle }).game.client;
        const me = client.sample().view?.characters.find((c) => c.playerId === client.playerId);
        return me ? [me.position.x, me.position.y, me.position.z] : null;
      });
    await page.waitForFunction(() => {
      const client = (window as unknown as { game?: PlayHandle }).game?.client;
      return client?.sample().view?.characters.some((c) => c.playerId === client.playerId) ?? false;
    }, null, { timeout: 30_000, polling: 100 });
    const pixels = await canvasPixels(page, 'canvas#view', 240);
    expect(fractionUnlike(pixels, dominantColor(pixels))).toBeGreaterThan(0.05); // not one flat colour: the room is drawn
    const start = (await mine())!;
    await page.locator('canvas#view').focus();
    await page.keyboard.down('KeyW');
    await page.waitForTimeout(1500);
    await page.keyboard.up('KeyW');
    await page.waitForTimeout(500);
    const end = (await mine())!;
    expect(Math.hypot(end[0] - start[0], end[2] - start[2])).toBeGreaterThan(1); // 4 m/s for 1.5 s when unloaded
    expect(errors).toEqual([]);
  });
});
