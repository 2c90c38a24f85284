// Browser test of the lobby: "create room" with a chosen scenario and parameters (ranges from GET /api/scenarios)
// opens that room on the server and joins it; an out-of-range value is refused on the page; "join by code" joins the
// same room from a second page.
import { afterAll, beforeAll, expect, it } from 'vitest';
import type { TaosState } from '../../client/app/test-hook.ts';
import type { RunningServer } from '../../server/start-server.ts';
import { buildClient } from '../../scripts/build-client.ts';
import { describeBrowser, launchBrowser, readHook, startAppServer, waitForHook, type BrowserSession } from '../helpers/browser.ts';

describeBrowser('lobby', () => {
  let browser: BrowserSession;
  let server: RunningServer;

  beforeAll(async () => {
    const built = await buildClient();
    server = await startAppServer({ scenario: 'shape-rain', clientDir: built.outDir, params: { count: 4 } });
    browser = await launchBrowser();
  });

  afterAll(async () => {
    await browser?.close();
    await server?.close('test over');
  });

  it('creates a room with the chosen scenario and parameters and joins it; another page joins it by code', async () => {
    const { page, errors } = await browser.newPage();
    await page.goto(new URL('/?name=maker&hud=0', server.url).href);
    await page.waitForSelector('#start:not([hidden]) #create-room', { timeout: 15_000 });
    await page.selectOption('#scenario-picker', 'pendulum-chain');
    // The parameters and their ranges come from the server's scenario list.
    await expect(page.locator('#create .param').count()).resolves.toBe(6);
    await expect(page.locator('label.param:has(#param-pinsPerChain) .range').textContent()).resolves.toBe('0–20');
    await page.fill('#param-chains', '2');
    await page.fill('#param-pinsPerChain', '25');
    await page.fill('#room-code', 'swing');
    await page.click('#create-room button[type="submit"]');
    await expect(page.locator('#create .form-error').textContent()).resolves.toBe('pinsPerChain must be between 0 and 20');
    expect((await fetch(new URL('/api/rooms/swing', server.url))).status).toBe(404);

    await page.fill('#param-pinsPerChain', '3');
    await page.click('#create-room button[type="submit"]');
    await waitForHook(page, "t.connected && t.roomId === 'swing' && t.scenario === 'pendulum-chain'");
    expect(new URL(page.url()).searchParams.get('room')).toBe('swing');
    const room = (await (await fetch(new URL('/api/rooms/swing', server.url))).json()) as { room: { scenario: string; params: Record<string, number> } };
    expect(room.room.scenario).toBe('pendulum-chain');
    expect(room.room.params).toMatchObject({ chains: 2, pinsPerChain: 3, links: 12 });

    const other = await browser.newPage();
    await other.page.goto(new URL('/?name=guest&hud=0', server.url).href);
    await other.page.waitForSelector('#start:not([hidden]) #join-code', { timeout: 15_000 });
    await other.page.fill('#join-code', 'swing');
    await other.page.click('#join-code-form button');
    await waitForHook(other.page, "t.connected && t.roomId === 'swing'");
    const hook = await readHook<TaosState>(other.page);
    expect(hook.scenario).toBe('pendulum-chain');
    // The maker was there first: its name comes from the room's player list and tags its character.
    await other.page.waitForFunction(() => [...document.querySelectorAll('#tags .tag')].some((t) => t.textContent === 'maker' && !(t as HTMLElement).hidden), null, { timeout: 15_000 });
    expect(errors).toEqual([]);
  });
});
