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
import { canvasPixels, describeBrowser, dominantColor, fractionChanged, fractionUnlike, launchBrowser, type BrowserSession } from '../helpers/browser.ts';
import { writeGameModule } from '../helpers/game-module.ts';

describeBrowser('kit', () => {
  let dir = '';
  let browser: BrowserSession;
  let server: RunningServer;

  beforeAll(async () => {
    dir = await mkdtemp(join(tmpdir(), 'taos-kit-'));
    const built = await buildClient({ outDir: join(dir, 'client') });
    await mkdir(join(dir, 'page'));
    await writeFile(join(dir, 'page', 'index.html'), scaffoldFiles({ name: 'crate-drop', dependency: '*' })['page/index.html']);
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

  it("draws the game's room on its own page and moves the player's view when W is held", async () => {
    const { page, errors } = await browser.newPage();
    await page.goto(server.url);
    await page.waitForFunction(() => document.getElementById('score')?.textContent?.startsWith('goals: 0'), null, { timeout: 30_000 });
    await page.waitForTimeout(2500); // the crate lands and sleeps
    const before = await canvasPixels(page, 'canvas#view', 240);
    expect(fractionUnlike(before, dominantColor(before))).toBeGreaterThan(0.05);
    await page.locator('canvas#view').focus();
    await page.keyboard.down('KeyW');
    await page.waitForTimeout(1200);
    await page.keyboard.up('KeyW');
    const after = await canvasPixels(page, 'canvas#view', 240);
    expect(fractionChanged(before, after)).toBeGreaterThan(0.04); // measured: ~0.09 walking, ~0.01 standing
    expect(errors).toEqual([]);
  });
});
