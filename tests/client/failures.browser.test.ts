// Browser tests of the page's failure messages: the server's API is unreachable, the room does not exist, and the
// server shuts down under a connected page. Each ends in a clear message, never a blank or frozen page.
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
      await expect(page.locator('#message button').textContent()).resolves.toBe('Try again');
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
      await missing.page.close();

      const { page, errors } = await browser.newPage();
      await page.goto(new URL('/?room=', server.url).href);
      await waitForHook(page, 't.connected && t.framesRendered >= 2');
      await server.close('server-shutdown');
      await waitForHook(page, '!t.connected', 15_000);
      await expect(page.locator('#message h2').textContent()).resolves.toBe('Connection lost');
      await expect(page.locator('#message p').textContent()).resolves.toMatch(/server-shutdown[\s\S]*Reconnecting \(attempt 1\)/);
      expect((await readHook<TaosState>(page)).page).toBe('connecting');
      expect(errors.filter((e) => !/WebSocket|ERR_CONNECTION_REFUSED/.test(e))).toEqual([]);
      await page.close();
    } finally {
      await server.close('test over');
    }
  });
});
