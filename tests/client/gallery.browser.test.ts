// Browser test of the renderer alone (no server): the gallery page in headless Chromium creates a WebGPU device,
// renders every shape kind without console errors, and its pixels show moving bodies.
import { afterAll, beforeAll, expect, it } from 'vitest';
import { buildClient } from '../../scripts/build-client.ts';
import { canvasPixels, describeBrowser, dominantColor, fractionChanged, fractionUnlike, launchBrowser, readHook, serveDirectory, type BrowserSession } from '../helpers/browser.ts';
import type { TaosState } from '../../client/app/test-hook.ts';

describeBrowser('gallery page', () => {
  let browser: BrowserSession;
  let site: { url: string; close: () => Promise<void> };

  beforeAll(async () => {
    const built = await buildClient();
    site = await serveDirectory(built.outDir);
    browser = await launchBrowser();
  });

  afterAll(async () => {
    await browser?.close();
    await site?.close();
  });

  it('renders every shape kind on a SwiftShader WebGPU device, with moving pixels and no console errors', async () => {
    const { page, errors } = await browser.newPage();
    await page.goto(`${site.url}/gallery.html`);
    await page.waitForFunction(() => {
      const t = (globalThis as { __taos?: TaosState }).__taos;
      return !!t && (t.framesRendered >= 3 || t.error !== null);
    }, null, { timeout: 30_000 });
    const hook = await readHook<TaosState>(page);
    expect(hook.error).toBeNull();
    expect(hook.adapter).not.toBeNull();
    expect(hook.adapter!.architecture.length + hook.adapter!.vendor.length).toBeGreaterThan(0);
    expect(hook.bodies.length).toBe(6);

    const first = await canvasPixels(page);
    const background = dominantColor(first);
    // The ground, terrain and shapes cover a good part of the view; the sky is the rest.
    expect(fractionUnlike(first, background)).toBeGreaterThan(0.2);
    await page.waitForTimeout(700);
    const second = await canvasPixels(page);
    const moved = fractionChanged(first, second);
    expect(moved).toBeGreaterThan(0.002);
    const later = await readHook<TaosState>(page);
    expect(later.framesRendered).toBeGreaterThan(hook.framesRendered);
    const y0 = hook.bodies.map((b) => b.position[1]);
    const y1 = later.bodies.map((b) => b.position[1]);
    expect(y1).not.toEqual(y0);
    // The hook is read-only: assigning it throws, and what it returns is frozen.
    const tamper = await page.evaluate(() => {
      const g = globalThis as unknown as { __taos: { framesRendered: number } };
      let assign = 'assigned';
      try {
        g.__taos = { framesRendered: -1 };
      } catch (e) {
        assign = (e as Error).message;
      }
      const snapshot = g.__taos;
      try {
        snapshot.framesRendered = -1;
      } catch {
        // strict-mode write to a frozen object
      }
      return { assign, frozen: Object.isFrozen(snapshot), frames: g.__taos.framesRendered };
    });
    expect(tamper.assign).toBe('window.__taos is read-only');
    expect(tamper.frozen).toBe(true);
    expect(tamper.frames).toBeGreaterThan(0);
    expect(errors).toEqual([]);
    await page.close();
  });

  it('keeps rendering at the new size after the window is resized', async () => {
    const { page, errors } = await browser.newPage();
    await page.goto(`${site.url}/gallery.html`);
    await page.waitForFunction(() => ((globalThis as { __taos?: TaosState }).__taos?.framesRendered ?? 0) >= 2, null, { timeout: 30_000 });
    await page.setViewportSize({ width: 400, height: 300 });
    const frames = (await readHook<TaosState>(page)).framesRendered;
    await page.waitForFunction((n) => ((globalThis as { __taos?: TaosState }).__taos?.framesRendered ?? 0) >= n + 3, frames, { timeout: 30_000 });
    const size = await page.evaluate(() => {
      const c = document.getElementById('scene') as HTMLCanvasElement;
      return [c.width / devicePixelRatio, c.height / devicePixelRatio];
    });
    expect(size).toEqual([400, 300]);
    const px = await canvasPixels(page);
    expect(px.width / px.height).toBeCloseTo(400 / 300, 1);
    expect(fractionUnlike(px, dominantColor(px))).toBeGreaterThan(0.2);
    expect(errors).toEqual([]);
    await page.close();
  });

  it('shows a clear message when the browser has no WebGPU', async () => {
    const { page, errors } = await browser.newPage();
    await page.addInitScript(() => {
      Object.defineProperty(Navigator.prototype, 'gpu', { get: () => undefined, configurable: true });
    });
    await page.goto(`${site.url}/gallery.html`);
    await page.waitForFunction(() => (globalThis as { __taos?: TaosState }).__taos?.error != null, null, { timeout: 15_000 });
    const hook = await readHook<TaosState>(page);
    expect(hook.error).toMatch(/no WebGPU/);
    await expect(page.locator('#message h2').textContent()).resolves.toBe('WebGPU is not available');
    expect(await page.locator('#message').isVisible()).toBe(true);
    expect(errors).toEqual([]);
    await page.close();
  });
});
