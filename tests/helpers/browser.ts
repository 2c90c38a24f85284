// Browser-test helpers: headless Debian Chromium with WebGPU on SwiftShader (CHROMIUM_FLAGS below),
// a loopback static server for the built client, console-error capture and in-page decoding of canvas screenshots.
import { existsSync } from 'node:fs';
import { mkdtemp, rm } from 'node:fs/promises';
import { createServer, type Server } from 'node:http';
import type { AddressInfo } from 'node:net';
import { tmpdir } from 'node:os';
import { join } from 'node:path';
import { chromium, type BrowserContext, type Page } from 'playwright-core';
import { describe, it } from 'vitest';
import { mat4LookAt, mat4Multiply, mat4Perspective, mat4TransformPoint, type Vec3 } from '../../client/render/mat4.ts';
import { silentLogger } from '../../server/logger.ts';
import { createMetrics } from '../../server/metrics.ts';
import { startServer, type RunningServer } from '../../server/start-server.ts';
import { createStaticHandler } from '../../server/static-files.ts';

/** Where the browser is looked for (override with CHROMIUM_PATH). */
export const CHROMIUM_PATH = process.env.CHROMIUM_PATH ?? '/usr/bin/chromium';

/**
 * Flags that give a presenting WebGPU canvas on SwiftShader and keep Chromium off the network. `--enable-unsafe-webgpu`
 * exposes the SwiftShader adapter (blocklisted otherwise); without the three ANGLE/Vulkan flags offscreen WebGPU works
 * but the canvas cannot present (the device is lost and screenshots stay blank); the background-networking flags stop
 * Chromium's own connections, which a closed network refuses.
 */
export const CHROMIUM_FLAGS: readonly string[] = [
  '--headless=new',
  '--no-sandbox',
  '--disable-gpu-sandbox',
  '--no-first-run',
  '--disable-quic',
  '--disable-background-networking',
  '--disable-component-update',
  '--disable-sync',
  '--enable-unsafe-webgpu',
  '--use-angle=swiftshader',
  '--enable-features=Vulkan',
  '--use-vulkan=swiftshader',
];

/** Test viewport: software WebGPU is slow, keep it small. */
export const VIEWPORT = { width: 640, height: 360 } as const;

/** Why browser tests cannot run here, or null when they can. */
export function browserMissingReason(): string | null {
  if (!existsSync(CHROMIUM_PATH)) return `Chromium not found at ${CHROMIUM_PATH} (install Debian's chromium: apt-get install -y chromium, or set CHROMIUM_PATH)`;
  return null;
}

/**
 * A describe block for browser tests: runs when Chromium is present; without it, fails under CI=true and is skipped
 * with a clear message otherwise.
 */
export function describeBrowser(name: string, body: () => void): void {
  const missing = browserMissingReason();
  if (!missing) {
    describe(name, body);
    return;
  }
  if (process.env.CI === 'true') {
    describe(name, () => {
      it('needs a browser', () => {
        throw new Error(`browser tests cannot run: ${missing}; CI=true, so this is a failure, not a skip`);
      });
    });
    return;
  }
  console.warn(`[browser tests skipped] ${name}: ${missing}`);
  describe.skip(name, body);
}

/** A running Chromium with a throw-away profile. */
export interface BrowserSession {
  context: BrowserContext;
  /** A new page; its console errors and uncaught exceptions are collected in `errors`. */
  newPage(): Promise<{ page: Page; errors: string[] }>;
  close(): Promise<void>;
}

/** Launches Chromium with a fresh user-data-dir (deleted on close). */
export async function launchBrowser(): Promise<BrowserSession> {
  const profile = await mkdtemp(join(tmpdir(), 'taos-chromium-'));
  let context: BrowserContext;
  try {
    context = await chromium.launchPersistentContext(profile, {
      executablePath: CHROMIUM_PATH,
      headless: true,
      args: [...CHROMIUM_FLAGS],
      viewport: { ...VIEWPORT },
      timeout: 30_000,
    });
  } catch (err) {
    await rm(profile, { recursive: true, force: true });
    throw err;
  }
  return {
    context,
    async newPage() {
      const page = await context.newPage();
      const errors: string[] = [];
      page.on('console', (msg) => {
        if (msg.type() === 'error') errors.push(`console.error: ${msg.text()}`);
      });
      page.on('pageerror', (err) => errors.push(`uncaught: ${err.message}`));
      return { page, errors };
    },
    async close() {
      await context.close().catch(() => undefined);
      await rm(profile, { recursive: true, force: true });
    },
  };
}

/** Serves a directory on 127.0.0.1 (a secure context for WebGPU) at an ephemeral port. */
export async function serveDirectory(dir: string): Promise<{ url: string; close: () => Promise<void> }> {
  const handler = createStaticHandler(dir);
  const server: Server = createServer((req, res) => {
    handler(req, res)
      .then((answered) => {
        if (!answered) res.writeHead(405).end();
      })
      .catch(() => res.writeHead(500).end());
  });
  await new Promise<void>((resolve) => server.listen(0, '127.0.0.1', resolve));
  const { port } = server.address() as AddressInfo;
  return {
    url: `http://127.0.0.1:${port}`,
    close: () => new Promise<void>((resolve) => server.close(() => resolve())),
  };
}

/** RGBA pixels of the canvas as presented (a screenshot decoded in the page), downsampled to about `maxWidth`. */
export interface CanvasPixels {
  width: number;
  height: number;
  /** RGBA bytes, row-major. */
  rgba: Uint8Array;
}

/** Screenshots the page's canvas after two animation frames and decodes it in the page. */
export async function canvasPixels(page: Page, selector = 'canvas#scene', maxWidth = 160): Promise<CanvasPixels> {
  await page.evaluate(() => new Promise<void>((resolve) => requestAnimationFrame(() => requestAnimationFrame(() => resolve()))));
  const box = await page.locator(selector).boundingBox();
  if (!box) throw new Error(`${selector} is not visible`);
  const png = await page.screenshot({ type: 'png', clip: box });
  const decoded = await page.evaluate(
    async ({ b64, maxW }) => {
      const bytes = Uint8Array.from(atob(b64), (c) => c.charCodeAt(0));
      const bitmap = await createImageBitmap(new Blob([bytes], { type: 'image/png' }));
      const w = Math.min(maxW, bitmap.width);
      const h = Math.max(1, Math.round((bitmap.height * w) / bitmap.width));
      const canvas = new OffscreenCanvas(w, h);
      const ctx = canvas.getContext('2d');
      if (!ctx) throw new Error('no 2d context for decoding');
      ctx.imageSmoothingEnabled = false;
      ctx.drawImage(bitmap, 0, 0, w, h);
      // Hand the bytes back as base64: a plain array of numbers is slow to serialize.
      const data = ctx.getImageData(0, 0, w, h).data;
      let binary = '';
      for (let i = 0; i < data.length; i += 0x8000) binary += String.fromCharCode(...data.subarray(i, i + 0x8000));
      return { width: w, height: h, rgba: btoa(binary) };
    },
    { b64: png.toString('base64'), maxW: maxWidth },
  );
  return { width: decoded.width, height: decoded.height, rgba: new Uint8Array(Buffer.from(decoded.rgba, 'base64')) };
}

/** Fraction of pixels that differ from `rgb` by more than `tolerance` on some channel. */
export function fractionUnlike(px: CanvasPixels, rgb: readonly [number, number, number], tolerance = 12): number {
  let differ = 0;
  const n = px.width * px.height;
  for (let i = 0; i < n; i++) {
    const o = i * 4;
    if (Math.abs(px.rgba[o] - rgb[0]) > tolerance || Math.abs(px.rgba[o + 1] - rgb[1]) > tolerance || Math.abs(px.rgba[o + 2] - rgb[2]) > tolerance) differ++;
  }
  return differ / n;
}

/** Fraction of pixels that differ between two same-sized captures by more than `tolerance` on some channel. */
export function fractionChanged(a: CanvasPixels, b: CanvasPixels, tolerance = 12): number {
  if (a.width !== b.width || a.height !== b.height) throw new Error(`captures differ in size: ${a.width}×${a.height} vs ${b.width}×${b.height}`);
  let changed = 0;
  const n = a.width * a.height;
  for (let i = 0; i < n * 4; i += 4) {
    if (Math.abs(a.rgba[i] - b.rgba[i]) > tolerance || Math.abs(a.rgba[i + 1] - b.rgba[i + 1]) > tolerance || Math.abs(a.rgba[i + 2] - b.rgba[i + 2]) > tolerance) changed++;
  }
  return changed / n;
}

/** The most common colour of a capture (the background, in practice). */
export function dominantColor(px: CanvasPixels): [number, number, number] {
  const counts = new Map<number, number>();
  for (let i = 0; i < px.rgba.length; i += 4) {
    const key = ((px.rgba[i] >> 3) << 10) | ((px.rgba[i + 1] >> 3) << 5) | (px.rgba[i + 2] >> 3);
    counts.set(key, (counts.get(key) ?? 0) + 1);
  }
  let best = 0;
  let bestCount = -1;
  for (const [key, count] of counts) {
    if (count > bestCount) {
      best = key;
      bestCount = count;
    }
  }
  return [((best >> 10) & 31) * 8 + 4, ((best >> 5) & 31) * 8 + 4, (best & 31) * 8 + 4];
}

/** Reads the page's read-only test hook. */
export async function readHook<T = Record<string, unknown>>(page: Page): Promise<T> {
  return page.evaluate(() => JSON.parse(JSON.stringify((globalThis as { __taos?: unknown }).__taos ?? null)) as never);
}

/** A camera as the page's hook reports it. */
export interface HookCamera {
  eye: number[];
  target: number[];
  fovYRadians: number;
  nearMetres: number;
  farMetres: number;
  widthPx: number;
  heightPx: number;
}

/** Where a world point lands on the canvas, as fractions of its width and height (0,0 = top left); null if behind. */
export function projectToCanvas(camera: HookCamera, point: readonly [number, number, number]): { x: number; y: number } | null {
  const proj = mat4Perspective(camera.fovYRadians, camera.widthPx / camera.heightPx, camera.nearMetres, camera.farMetres);
  const view = mat4LookAt(camera.eye as Vec3, camera.target as Vec3, [0, 1, 0]);
  const v = mat4TransformPoint(view, [point[0], point[1], point[2]]);
  if (v[2] >= -camera.nearMetres) return null;
  const c = mat4TransformPoint(mat4Multiply(proj, view), [point[0], point[1], point[2]]);
  return { x: (c[0] + 1) / 2, y: (1 - c[1]) / 2 };
}

/** Fraction of pixels that changed between two captures inside a square around (fx, fy) (fractions of the size). */
export function regionChanged(a: CanvasPixels, b: CanvasPixels, fx: number, fy: number, halfSizePx: number, tolerance = 12): number {
  const cx = Math.round(fx * a.width);
  const cy = Math.round(fy * a.height);
  let changed = 0;
  let total = 0;
  for (let y = Math.max(0, cy - halfSizePx); y <= Math.min(a.height - 1, cy + halfSizePx); y++) {
    for (let x = Math.max(0, cx - halfSizePx); x <= Math.min(a.width - 1, cx + halfSizePx); x++) {
      const i = (y * a.width + x) * 4;
      total++;
      if (Math.abs(a.rgba[i] - b.rgba[i]) > tolerance || Math.abs(a.rgba[i + 1] - b.rgba[i + 1]) > tolerance || Math.abs(a.rgba[i + 2] - b.rgba[i + 2]) > tolerance) changed++;
    }
  }
  return total === 0 ? 0 : changed / total;
}

/**
 * Starts the real server in-process on a loopback port 0, serving `clientDir`, quiet. The input flood limit keeps its
 * rate but gets a deeper burst: the server shares this process with the test and two software-rendering browsers,
 * and when it stalls for a couple of seconds a client's on-time inputs arrive all at once.
 */
export async function startAppServer(opts: { scenario: string; clientDir: string; params?: Record<string, number>; netMode?: 'snapshot' | 'predict' | 'auto'; recordDir?: string; recordHashEveryTicks?: number }): Promise<RunningServer> {
  return startServer({
    port: 0,
    host: '127.0.0.1',
    scenario: opts.scenario,
    params: opts.params,
    netMode: opts.netMode,
    clientDir: opts.clientDir,
    recordDir: opts.recordDir,
    recordHashEveryTicks: opts.recordHashEveryTicks,
    logger: silentLogger(),
    metrics: createMetrics({ processMetrics: false }),
    limits: { inputs: { perSecond: 150, burst: 1200 }, messages: { perSecond: 300, burst: 2400 } },
  });
}

/** Creates a room through the HTTP API (POST /api/rooms); throws with the server's answer on refusal. */
export async function createRoom(baseUrl: string, body: { scenario: string; roomId: string; params?: Record<string, number>; netMode?: 'snapshot' | 'predict' | 'auto' }): Promise<void> {
  const res = await fetch(new URL('/api/rooms', baseUrl), { method: 'POST', headers: { 'content-type': 'application/json' }, body: JSON.stringify(body), signal: AbortSignal.timeout(10_000) });
  if (!res.ok) throw new Error(`creating room ${body.roomId}: ${res.status} ${await res.text()}`);
}

/** Waits until the page's hook satisfies `predicate` (evaluated in the page on the hook object). */
export async function waitForHook(page: Page, predicate: string, timeoutMs = 30_000): Promise<void> {
  await page.waitForFunction(`(() => { const t = globalThis.__taos; return !!t && (${predicate}); })()`, null, { timeout: timeoutMs, polling: 100 });
}

/** Euclidean distance of two 3-vectors. */
export function distance3(a: readonly number[], b: readonly number[]): number {
  return Math.hypot(a[0] - b[0], a[1] - b[1], a[2] - b[2]);
}

/** Waits until a player's character has stood still in a page's hook for a quarter second; returns its position. */
export async function waitUntilStill(page: Page, playerId: number, timeoutMs = 15_000): Promise<number[]> {
  let last: number[] | null = null;
  const deadline = Date.now() + timeoutMs;
  while (Date.now() < deadline) {
    await page.waitForTimeout(250);
    const hook = await readHook<{ characters: Array<{ playerId: number; position: number[] }> }>(page);
    const pos = hook.characters.find((c) => c.playerId === playerId)?.position ?? null;
    if (pos && last && distance3(pos, last) < 0.01) return pos;
    last = pos;
  }
  throw new Error(`player ${playerId} never stood still within ${timeoutMs} ms`);
}

/** Number of pixels whose colour passes `test` (r, g, b in 0–255). */
export function countPixels(px: CanvasPixels, test: (r: number, g: number, b: number) => boolean): number {
  let n = 0;
  for (let i = 0; i < px.rgba.length; i += 4) if (test(px.rgba[i], px.rgba[i + 1], px.rgba[i + 2])) n++;
  return n;
}

/** Frame figures of a page over a window: frames drawn, mean/p50/p95 frame interval and our CPU time per frame. */
export interface FrameMeasurement {
  frames: number;
  meanIntervalMs: number;
  p50IntervalMs: number;
  p95IntervalMs: number;
  meanCpuMs: number;
  p95CpuMs: number;
  /** Navigation start → first frame with the world in it (ms), from the hook. */
  firstFrameMs: number | null;
}

/** Samples the page's frame timing for `windowMs` (the hook keeps the last 240 frames; read at the end). */
export async function measureFrames(page: Page, windowMs: number): Promise<FrameMeasurement> {
  type Hook = { framesRendered: number; firstFrameMs: number | null; frameTiming: Omit<FrameMeasurement, 'frames' | 'firstFrameMs'> };
  const start = await readHook<Hook>(page);
  await page.waitForTimeout(windowMs);
  const end = await readHook<Hook>(page);
  const t = end.frameTiming;
  return { frames: end.framesRendered - start.framesRendered, meanIntervalMs: t.meanIntervalMs, p50IntervalMs: t.p50IntervalMs, p95IntervalMs: t.p95IntervalMs, meanCpuMs: t.meanCpuMs, p95CpuMs: t.p95CpuMs, firstFrameMs: end.firstFrameMs };
}
