// Browser test of the follow camera in every scenario: from where each scenario spawns the player, the player's own
// capsule covers less than 15 % of the frame (the camera is never inside or right behind it). The screenshots are the
// ones `npm run gallery` writes to docs/img/.
import { afterAll, beforeAll, expect, it } from 'vitest';
import { scenarioNames } from '../../scenarios/index.ts';
import type { RunningServer } from '../../server/start-server.ts';
import { buildClient } from '../../scripts/build-client.ts';
import { describeBrowser, launchBrowser, startAppServer, type BrowserSession } from '../helpers/browser.ts';
import { shootScenarios } from '../helpers/scenario-shots.ts';

describeBrowser('follow camera', () => {
  let browser: BrowserSession;
  let server: RunningServer;

  beforeAll(async () => {
    const built = await buildClient();
    server = await startAppServer({ scenario: 'shape-rain', clientDir: built.outDir, params: { count: 1 } });
    browser = await launchBrowser();
  });

  afterAll(async () => {
    await browser?.close();
    await server?.close('test over');
  });

  it('keeps the own avatar under 15 % of the frame in every scenario', async () => {
    const shots = await shootScenarios(browser, server.url, scenarioNames());
    const coverage = Object.fromEntries(shots.map((s) => [s.scenario, Math.round(s.ownAvatarCoverage * 1000) / 1000]));
    console.log('own avatar coverage per scenario:', coverage);
    expect(shots.filter((s) => !(s.ownAvatarCoverage < 0.15)).map((s) => `${s.scenario}: ${(s.ownAvatarCoverage * 100).toFixed(1)} %`)).toEqual([]);
  }, 300_000);
});
