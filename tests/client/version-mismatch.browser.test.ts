// Browser test of the page's version-mismatch ending, both ways round, against a real server whose frames are
// rewritten in flight (Playwright's WebSocket routing): a page older than the server (its hello claims the previous
// protocol, the server refuses it) and a page older than the server's welcome (the welcome claims the next protocol).
// Either way the page says it is out of date, offers a reload and the way back, and never loops reconnecting.
import { afterAll, beforeAll, expect, it } from 'vitest';
import type { Page } from 'playwright-core';
import type { TaosState } from '../../client/app/test-hook.ts';
import { buildClient } from '../../scripts/build-client.ts';
import { packValue, unpackFrame } from '../../shared/protocol/codec.ts';
import { ClientOpcode, ServerOpcode } from '../../shared/protocol/opcodes.ts';
import { PROTOCOL_VERSION } from '../../shared/protocol/index.ts';
import { describeBrowser, launchBrowser, readHook, startAppServer, waitForHook, type BrowserSession } from '../helpers/browser.ts';
import type { RunningServer } from '../../server/start-server.ts';

type Rewrite = { fromPage?: (value: unknown[]) => unknown[]; fromServer?: (value: unknown[]) => unknown[] };

// Passes every frame through between page and server, letting `rewrite` change decoded frames on the way.
async function routeThrough(page: Page, rewrite: Rewrite): Promise<{ socketsOpened: () => number }> {
  let opened = 0;
  await page.routeWebSocket((url) => url.protocol === 'ws:', (ws) => {
    opened++;
    const server = ws.connectToServer();
    const pass = (f: ((v: unknown[]) => unknown[]) | undefined, message: string | Buffer): string | Buffer => {
      if (!f || typeof message === 'string') return message;
      const value = unpackFrame(new Uint8Array(message)) as unknown[];
      return Buffer.from(packValue(f(value)));
    };
    ws.onMessage((m) => server.send(pass(rewrite.fromPage, m)));
    server.onMessage((m) => ws.send(pass(rewrite.fromServer, m)));
  });
  return { socketsOpened: () => opened };
}

async function expectOutOfDate(page: Page, detail: RegExp, socketsOpened: () => number): Promise<void> {
  await waitForHook(page, "t.page === 'closed'", 15_000);
  await expect(page.locator('#message h2').textContent()).resolves.toBe('This page is out of date');
  await expect(page.locator('#message p').textContent()).resolves.toMatch(detail);
  await expect(page.locator('#message button').allTextContents()).resolves.toEqual(['Try again', 'Back to rooms']);
  // Retrying the same socket cannot help: two seconds later it still says so, after one socket only.
  await page.waitForTimeout(2000);
  const after = await readHook<TaosState>(page);
  expect(after.page).toBe('closed');
  expect(after.connected).toBe(false);
  expect(socketsOpened()).toBe(1);
}

describeBrowser('version mismatch', () => {
  let browser: BrowserSession;
  let server: RunningServer;

  beforeAll(async () => {
    const clientDir = (await buildClient()).outDir;
    browser = await launchBrowser();
    server = await startAppServer({ scenario: 'shape-rain', clientDir, params: { count: 20 } });
  });

  afterAll(async () => {
    await server?.close('test over');
    await browser?.close();
  });

  it('says the page is out of date when the server refuses its hello for an older protocol', async () => {
    const { page } = await browser.newPage();
    const route = await routeThrough(page, {
      fromPage: (v) => (v[0] === ClientOpcode.Hello ? [v[0], PROTOCOL_VERSION - 1, ...v.slice(2)] : v),
    });
    await page.goto(new URL('/?room=&name=old', server.url).href);
    await expectOutOfDate(page, new RegExp(`speaks protocol ${PROTOCOL_VERSION} and the client sent protocol ${PROTOCOL_VERSION - 1}`), route.socketsOpened);
    // The way back leads to the room list.
    await page.locator('#message button', { hasText: 'Back to rooms' }).click();
    await page.waitForSelector('#start:not([hidden]) #rooms button', { timeout: 15_000 });
    await page.close();
  });

  it('says the page is out of date when the server welcomes it with a newer protocol', async () => {
    const { page } = await browser.newPage();
    const route = await routeThrough(page, {
      fromServer: (v) => (v[0] === ServerOpcode.Welcome ? [v[0], { ...(v[1] as object), protocolVersion: PROTOCOL_VERSION + 1 }, ...v.slice(2)] : v),
    });
    await page.goto(new URL('/?room=&name=behind', server.url).href);
    await expectOutOfDate(page, new RegExp(`server speaks protocol ${PROTOCOL_VERSION + 1}`), route.socketsOpened);
    await page.close();
  });
});
