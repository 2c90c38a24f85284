// Browser tests of the page's failure messages: the server's API is unreachable, the room does not exist, an operator
// kicks the player, and the server shuts down under a connected page. Each ends in a clear message with a way back,
// never a blank or frozen page, and never a reconnect loop.
import { afterAll, beforeAll, expect, it } from 'vitest';
import type { TaosState } from '../../client/app/test-hook.ts';
import { buildClient } from '../../scripts/build-client.ts';
import { describeBrowser, launchBrowser, readHook, serveDirectory, startAppServer, waitForHook, type BrowserSession } from '../helpers/browser.ts';

describeBrowser('failure messages', () => {
  let browser: BrowserSession;
  let clientDir: string;

  beforeAll(async () => {
    clientDir = (await buildClient()).outDir;
    browser = await launchBrowser();
  });

  afterAll(async () => {
    await browser?.close();
  });

  it('says the server is unreachable when the page is served without its API', async () => {
    const site = await serveDirectory(clientDir);
    try {
      const { page, errors } = await browser.newPage();
      await page.goto(site.url);
      await waitForHook(page, "t.page === 'error'", 15_000);
      await expect(page.locator('#message h2').textContent()).resolves.toBe('Server unreachable');
      await expect(page.locator('#message p').textContent()).resolves.toMatch(/Cannot reach the server at http:\/\/127\.0\.0\.1:\d+ \(.*404/);
      await expect(page.locator('#message button').allTextContents()).resolves.toEqual(['Try again']);
      // The failed API request itself is the only console error (the browser logs the 404).
      expect(errors.filter((e) => !/404/.test(e))).toEqual([]);
      await page.close();
    } finally {
      await site.close();
    }
  });

  it('says so when the room does not exist, and when the server shuts down under a connected page', async () => {
    const server = await startAppServer({ scenario: 'shape-rain', clientDir, params: { count: 20 } });
    try {
      const missing = await browser.newPage();
      await missing.page.goto(new URL('/?room=nowhere', server.url).href);
      await waitForHook(missing.page, "t.page === 'closed'", 15_000);
      await expect(missing.page.locator('#message h2').textContent()).resolves.toBe('No such room');
      await expect(missing.page.locator('#message p').textContent()).resolves.toMatch(/nowhere/);
      expect((await readHook<TaosState>(missing.page)).connected).toBe(false);
      // Retrying a missing room cannot help: the only way out is back to the room list, which then shows.
      await expect(missing.page.locator('#message button').allTextContents()).resolves.toEqual(['Back to rooms']);
      await missing.page.locator('#message button').click();
      await missing.page.waitForSelector('#start:not([hidden]) #rooms button', { timeout: 15_000 });
      expect(new URL(missing.page.url()).searchParams.has('room')).toBe(false);
      await missing.page.close();

      // An operator removes a player (the monitor's kick): the page says so, offers only the way back, and stays put.
      const kicked = await browser.newPage();
      await kicked.page.goto(new URL('/?room=&name=rowdy', server.url).href);
      await waitForHook(kicked.page, 't.connected && t.playerId !== null');
      const rowdy = (await readHook<TaosState>(kicked.page)).playerId!;
      const kick = await fetch(new URL(`/monitor/rooms/default/players/${rowdy}/kick`, server.url), { method: 'POST' });
      expect(kick.status).toBe(200);
      await waitForHook(kicked.page, "t.page === 'closed'", 15_000);
      await expect(kicked.page.locator('#message h2').textContent()).resolves.toBe('You were removed from the room');
      await expect(kicked.page.locator('#message p').textContent()).resolves.toMatch(/kicked: an operator removed you from the room/);
      await expect(kicked.page.locator('#message button').allTextContents()).resolves.toEqual(['Back to rooms']);
      await kicked.page.close();

      const { page, errors } = await browser.newPage();
      await page.goto(new URL('/?room=', server.url).href);
      await waitForHook(page, 't.connected && t.framesRendered >= 2');
      const reconnectMessages: string[] = [];
      await page.exposeFunction('__sawReconnect', (text: string) => reconnectMessages.push(text));
      // Records every "Connection lost" the page would show, however briefly.
      await page.evaluate(() => {
        const box = document.getElementById('message')!;
        new MutationObserver(() => {
          const h = box.querySelector('h2')?.textContent ?? '';
          if (/Connection lost|Reconnecting/.test(box.textContent ?? '')) (window as unknown as { __sawReconnect(t: string): void }).__sawReconnect(h);
        }).observe(box, { childList: true, subtree: true, characterData: true });
      });
      await server.close('maintenance');
      await waitForHook(page, "t.page === 'closed'", 15_000);
      await expect(page.locator('#message h2').textContent()).resolves.toBe('The server shut down');
      await expect(page.locator('#message p').textContent()).resolves.toMatch(/server-shutdown: maintenance/);
      await expect(page.locator('#message button').allTextContents()).resolves.toEqual(['Try again', 'Back to rooms']);
      // No reconnect loop: two seconds later the page still says the same and never showed a reconnect.
      await page.waitForTimeout(2000);
      const after = await readHook<TaosState>(page);
      expect(after.page).toBe('closed');
      expect(after.connected).toBe(false);
      await expect(page.locator('#message h2').textContent()).resolves.toBe('The server shut down');
      expect(reconnectMessages).toEqual([]);
      expect(errors.filter((e) => !/WebSocket|ERR_CONNECTION_REFUSED/.test(e))).toEqual([]);
      await page.close();
    } finally {
      await server.close('test over');
    }
  });
});
