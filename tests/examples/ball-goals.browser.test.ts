// Browser test of examples/ball-goals' page (page/index.html on /kit.js): the page shows the replicated score, holding
// W and E walks the first player at the ball and kicks it into red's goal, and the score on the page changes.
import { mkdtemp, rm } from 'node:fs/promises';
import { tmpdir } from 'node:os';
import { join } from 'node:path';
import { fileURLToPath } from 'node:url';
import { afterAll, beforeAll, expect, it } from 'vitest';
import { scenario } from '../../examples/ball-goals/game.ts';
import { buildClient } from '../../scripts/build-client.ts';
import { scenarioSource } from '../../server/create-server.ts';
import { silentLogger } from '../../server/logger.ts';
import { startServer, type RunningServer } from '../../server/start-server.ts';
import { describeBrowser, launchBrowser, type BrowserSession } from '../helpers/browser.ts';

describeBrowser('ball-goals page', () => {
  let dir = '';
  let browser: BrowserSession;
  let server: RunningServer;

  beforeAll(async () => {
    dir = await mkdtemp(join(tmpdir(), 'taos-ball-goals-'));
    const built = await buildClient({ outDir: join(dir, 'client') });
    const pageDir = fileURLToPath(new URL('../../examples/ball-goals/page', import.meta.url));
    server = await startServer({ port: 0, scenarios: scenarioSource([scenario]), scenario: scenario.name, clientDir: built.outDir, pageDir, logger: silentLogger() });
    browser = await launchBrowser();
  });

  afterAll(async () => {
    await browser?.close();
    await server?.close('test over');
    await rm(dir, { recursive: true, force: true });
  });

  it('shows the score and counts a goal when the player walks at the ball holding the kick key', async () => {
    const { page, errors } = await browser.newPage();
    await page.goto(server.url);
    await page.waitForFunction(() => document.getElementById('score')?.textContent === 'red 0 · blue 0' && document.getElementById('status')?.textContent?.startsWith('room '), null, { timeout: 30_000 });
    await page.locator('canvas#view').focus();
    await page.keyboard.down('KeyE');
    await page.keyboard.down('KeyW');
    await page.waitForFunction(() => document.getElementById('score')?.textContent === 'red 0 · blue 1', null, { timeout: 30_000 });
    await page.keyboard.up('KeyW');
    await page.keyboard.up('KeyE');
    expect(await page.locator('#status').textContent()).toBe('goal for blue!');
    expect(errors).toEqual([]);
  });
});
