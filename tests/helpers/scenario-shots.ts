// Screenshots of every scenario as a player sees it, shared by the follow-camera browser test and the gallery script
// (scripts/gallery.ts): joins a room of the scenario, waits for the follow camera to settle, measures how much of the
// frame the player's own capsule covers (from the page's camera, conservatively: the clipped bounding box of the
// capsule's projected outline) and captures the canvas; then the orbit view (V).
import type { Page } from 'playwright-core';
import type { TaosState } from '../../client/app/test-hook.ts';
import { CHARACTER_HALF_HEIGHT_METRES, CHARACTER_RADIUS_METRES } from '../../shared/sim/players.ts';
import { projectToCanvas, readHook, waitForHook, type BrowserSession, type HookCamera } from './browser.ts';

/** How screenshots are encoded: PNG for tests (exact), JPEG for the committed gallery (small). */
export type ImageFormat = 'png' | 'jpeg';

/** What one scenario looked like. */
export interface ScenarioShot {
  scenario: string;
  /** Fraction of the follow view's frame the own capsule covers (1 when the camera is inside or behind it). */
  ownAvatarCoverage: number;
  /** The canvas in the follow view (PNG, or JPEG when asked). */
  follow: Buffer;
  /** The canvas in the orbit view. */
  orbit: Buffer;
  camera: HookCamera;
}

/** Parameters that keep software rendering quick while showing what each scenario is. */
export const SHOT_PARAMS: Readonly<Record<string, Record<string, number>>> = {
  'shape-rain': { count: 120 },
  'crowd-arena': { props: 48 },
  'cubes-901': {},
};

/** The fraction of the frame the capsule whose feet are at `feet` covers in `camera`'s view (an upper bound). */
export function capsuleCoverage(camera: HookCamera, feet: readonly number[]): number {
  const r = CHARACTER_RADIUS_METRES;
  const height = 2 * (CHARACTER_HALF_HEIGHT_METRES + r);
  const [ex, ey, ez] = camera.eye;
  // The eye inside the capsule's cylinder (caps included, as a box) sees nothing else.
  if (Math.hypot(ex - feet[0], ez - feet[2]) < r && ey > feet[1] && ey < feet[1] + height) return 1;
  let minX = Infinity;
  let minY = Infinity;
  let maxX = -Infinity;
  let maxY = -Infinity;
  for (let ring = 0; ring <= 8; ring++) {
    const y = feet[1] + (height * ring) / 8;
    // Caps narrow the outline; the full radius at every ring keeps the bound conservative.
    for (let k = 0; k < 16; k++) {
      const a = (k / 16) * Math.PI * 2;
      const p = projectToCanvas(camera, [feet[0] + r * Math.cos(a), y, feet[2] + r * Math.sin(a)]);
      if (p === null) return 1;
      minX = Math.min(minX, p.x);
      maxX = Math.max(maxX, p.x);
      minY = Math.min(minY, p.y);
      maxY = Math.max(maxY, p.y);
    }
  }
  const w = Math.max(0, Math.min(1, maxX) - Math.max(0, minX));
  const h = Math.max(0, Math.min(1, maxY) - Math.max(0, minY));
  return w * h;
}

async function settle(page: Page, frames: number): Promise<void> {
  const start = (await readHook<TaosState>(page)).framesRendered;
  await waitForHook(page, `t.framesRendered >= ${start + frames}`, 60_000);
}

/** Waits until the follow camera holds still (its easing is time-based, so a fast page needs more frames). */
async function settleCamera(page: Page): Promise<void> {
  let last: readonly number[] | null = null;
  for (let i = 0; i < 60; i++) {
    await settle(page, 4);
    const eye = ((await readHook<TaosState>(page)).camera as HookCamera).eye;
    if (last !== null && Math.hypot(eye[0] - last[0], eye[1] - last[1], eye[2] - last[2]) < 0.005) return;
    last = [...eye];
  }
}

/** Joins `roomId` (already open with `scenario`) in a fresh page and captures it. */
export async function shootScenario(browser: BrowserSession, serverUrl: string, roomId: string, scenario: string, image: ImageFormat = 'png'): Promise<ScenarioShot> {
  const { page } = await browser.newPage();
  try {
    await page.goto(new URL(`/?room=${encodeURIComponent(roomId)}&name=you&hud=0`, serverUrl).href);
    await waitForHook(page, 't.connected && t.camera !== null && t.characters.some((c) => c.playerId === t.playerId)', 60_000);
    // The follow camera eases in: let it settle before measuring.
    await settle(page, 12);
    await settleCamera(page);
    const hook = await readHook<TaosState>(page);
    const mine = hook.characters.find((c) => c.playerId === hook.playerId)!;
    const camera = hook.camera as HookCamera;
    const ownAvatarCoverage = capsuleCoverage(camera, mine.position);
    const shotOptions = image === 'jpeg' ? ({ type: 'jpeg', quality: 82 } as const) : ({ type: 'png' } as const);
    const follow = await page.locator('canvas#scene').screenshot(shotOptions);
    await page.keyboard.press('KeyV');
    await settle(page, 6);
    const orbit = await page.locator('canvas#scene').screenshot(shotOptions);
    return { scenario, ownAvatarCoverage, follow, orbit, camera };
  } finally {
    await page.close();
  }
}

/** Opens a room of each scenario in turn on `serverUrl` (POST /api/rooms), shoots it, and closes it again. */
export async function shootScenarios(browser: BrowserSession, serverUrl: string, scenarios: readonly string[], opts: { image?: ImageFormat; onShot?: (shot: ScenarioShot) => Promise<void> | void } = {}): Promise<ScenarioShot[]> {
  const shots: ScenarioShot[] = [];
  for (const scenario of scenarios) {
    const roomId = `shot-${scenario}`;
    const res = await fetch(new URL('/api/rooms', serverUrl), { method: 'POST', headers: { 'content-type': 'application/json' }, body: JSON.stringify({ scenario, roomId, params: SHOT_PARAMS[scenario] ?? {} }) });
    if (!res.ok) throw new Error(`opening ${scenario}: ${res.status} ${await res.text()}`);
    try {
      const shot = await shootScenario(browser, serverUrl, roomId, scenario, opts.image);
      shots.push(shot);
      await opts.onShot?.(shot);
    } finally {
      await fetch(new URL(`/api/rooms/${roomId}`, serverUrl), { method: 'DELETE' });
    }
  }
  return shots;
}
