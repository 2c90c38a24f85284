// Client decode cost of snapshots, in Node and in headless Chromium, on the same bytes: cubes-901 with the big cube
// pushed through the field (the bandwidth figure's driver), one client at 60 Hz with acks 100 ms late; the whole
// stream is decoded in order by a fresh SnapshotDecoder per pass and the loop is timed as a whole (Chromium coarsens
// performance.now() in a page that is not cross-origin isolated).
// Run: node bench/snapshot-decode-browser.ts [seconds=20] [passes=5]   (Chromium at CHROMIUM_PATH or /usr/bin/chromium)
import { mkdtemp, rm } from 'node:fs/promises';
import { tmpdir } from 'node:os';
import { join } from 'node:path';
import { build } from 'esbuild';
import { chromium } from 'playwright-core';
import { getScenario } from '../scenarios/index.ts';
import { createSnapshotFormat, quantizeFrame, snapshotFormatSpec, SnapshotDecoder, SnapshotEncoder, snapshotFormatFromSpec, type SnapshotFormatSpec } from '../shared/protocol/index.ts';
import type { Bounds } from '../shared/protocol/quantization.ts';
import { cubeDriver } from './figures/bandwidth.ts';
import { createSceneSim, CUBES_SCENE } from './lib/scenes.ts';

const seconds = Number(process.argv[2] ?? 20);
const passes = Number(process.argv[3] ?? 5);
const ACK_DELAY_TICKS = 6;
const WARM_TICKS = 120;

/** The encoded snapshots of one 60 Hz client from its join; the pushed part starts at index WARM_TICKS. */
async function pushedStream(): Promise<{ bounds: Bounds; spec: SnapshotFormatSpec; snapshots: Uint8Array[] }> {
  const bounds = getScenario(CUBES_SCENE.scenario).bounds;
  const format = createSnapshotFormat(bounds);
  const sim = await createSceneSim(CUBES_SCENE);
  try {
    const drive = cubeDriver(sim);
    const encoder = new SnapshotEncoder(format);
    encoder.markDescriptorsKnown(sim.descriptors().map((d) => d.id));
    const acks: Array<{ at: number; tick: number }> = [];
    const snapshots: Uint8Array[] = [];
    for (let t = 0; t < WARM_TICKS + seconds * 60; t++) {
      const record = drive(sim.tick);
      sim.step(record);
      while (acks.length > 0 && acks[0].at <= t) encoder.acknowledge(acks.shift()!.tick);
      const frame = quantizeFrame(format, sim.tick, sim.readBodyStates(), sim.characters());
      const encoded = encoder.encode(frame, (id) => sim.bodyDescriptor(id));
      acks.push({ at: t + ACK_DELAY_TICKS, tick: frame.tick });
      snapshots.push(encoded.bytes);
    }
    return { bounds, spec: snapshotFormatSpec(format), snapshots };
  } finally {
    sim.destroy();
  }
}

/** Decodes the stream `count` times in order; returns µs per snapshot from index `from` on, per pass. */
function decodePasses(bounds: Bounds, spec: SnapshotFormatSpec, snapshots: Uint8Array[], count: number, from: number): number[] {
  const out: number[] = [];
  for (let p = 0; p < count; p++) {
    const decoder = new SnapshotDecoder(snapshotFormatFromSpec(bounds, spec));
    for (let i = 0; i < from; i++) decoder.decode(snapshots[i]);
    const t0 = performance.now();
    for (let i = from; i < snapshots.length; i++) decoder.decode(snapshots[i]);
    out.push(((performance.now() - t0) * 1000) / (snapshots.length - from));
  }
  return out;
}

const { bounds, spec, snapshots } = await pushedStream();
const pushed = snapshots.slice(WARM_TICKS);
const meanBytes = pushed.reduce((n, s) => n + s.length, 0) / pushed.length;
const node = decodePasses(bounds, spec, snapshots, passes, WARM_TICKS);
const bundle = await build({
  stdin: {
    contents: `import { SnapshotDecoder, snapshotFormatFromSpec } from './shared/protocol/index.ts';\nglobalThis.decodePasses = ${decodePasses.toString()};`,
    resolveDir: process.cwd(),
    loader: 'ts',
  },
  bundle: true,
  format: 'iife',
  write: false,
  platform: 'browser',
});
const profile = await mkdtemp(join(tmpdir(), 'decode-bench-'));
let browser: number[] = [];
const context = await chromium.launchPersistentContext(profile, { executablePath: process.env.CHROMIUM_PATH ?? '/usr/bin/chromium', headless: true, args: ['--no-sandbox', '--disable-background-networking', '--disable-component-update'] });
try {
  const page = await context.newPage();
  await page.setContent(`<script>${bundle.outputFiles[0].text}</script>`);
  browser = await page.evaluate(
    ({ b, s, snaps, n, from }) => (globalThis as unknown as { decodePasses: typeof decodePasses }).decodePasses(b, s, snaps.map((x) => new Uint8Array(x)), n, from),
    { b: bounds, s: spec, snaps: snapshots.map((x) => Array.from(x)), n: passes, from: WARM_TICKS },
  );
} finally {
  await context.close();
  await rm(profile, { recursive: true, force: true });
}
const fmt = (xs: number[]): string => `best ${Math.min(...xs).toFixed(1)} µs, passes ${xs.map((x) => x.toFixed(1)).join(' ')}`;
console.log(`cubes-901 pushed, 60 Hz, ${pushed.length} snapshots of ${meanBytes.toFixed(1)} B mean`);
console.log(`decode per snapshot, Node ${process.version}: ${fmt(node)}`);
console.log(`decode per snapshot, Chromium: ${fmt(browser)}`);
