// The renderer gallery (gallery.html): every shape kind the renderer draws, moving on scripted paths, with no server.
// A visual check of the renderer and the scene browser tests use; `?count=N` adds N more bodies for load tests.
import type { ShapeSpec } from '../../shared/physics-data/shape-spec.ts';
import { OrbitCamera } from '../render/camera.ts';
import { WebGpuUnavailableError } from '../render/gpu-context.ts';
import { Renderer } from '../render/renderer.ts';
import { InstanceFlag } from '../render/shaders.ts';
import { FrameTimer } from './frame-timer.ts';
import { showMessage } from './overlay.ts';
import { installTestHook, type HookBody } from './test-hook.ts';

interface Mover {
  id: number;
  x: number;
  z: number;
  dropHeight: number;
  phase: number;
  spinAxis: [number, number, number];
}

/** A small deterministic generator (the gallery must look the same on every load). */
function lcg(seed: number): () => number {
  let s = seed >>> 0;
  return () => {
    s = (Math.imul(s, 1664525) + 1013904223) >>> 0;
    return s / 4294967296;
  };
}

function hullPoints(rand: () => number, radius: number, count: number): number[] {
  const pts: number[] = [];
  for (let i = 0; i < count; i++) {
    const u = rand() * 2 - 1;
    const a = rand() * Math.PI * 2;
    const r = Math.sqrt(1 - u * u);
    pts.push(r * Math.cos(a) * radius, u * radius * 0.8, r * Math.sin(a) * radius * 1.2);
  }
  return pts;
}

function shapes(rand: () => number): Array<[ShapeSpec, [number, number, number]]> {
  return [
    [{ kind: 'box', halfExtents: { x: 0.5, y: 0.35, z: 0.4 } }, [0.9, 0.3, 0.25]],
    [{ kind: 'sphere', radius: 0.5 }, [0.3, 0.45, 0.9]],
    [{ kind: 'capsule', halfHeight: 0.45, radius: 0.3 }, [0.95, 0.6, 0.2]],
    [{ kind: 'cylinder', halfHeight: 0.45, radius: 0.4 }, [0.45, 0.8, 0.35]],
    [{ kind: 'convexHull', points: hullPoints(rand, 0.55, 24) }, [0.6, 0.35, 0.85]],
    [
      {
        kind: 'compound',
        parts: [
          { shape: { kind: 'sphere', radius: 0.3 }, position: { x: -0.5, y: 0, z: 0 } },
          { shape: { kind: 'sphere', radius: 0.3 }, position: { x: 0.5, y: 0, z: 0 } },
          { shape: { kind: 'cylinder', halfHeight: 0.45, radius: 0.1 }, rotation: { x: 0, y: 0, z: Math.SQRT1_2, w: Math.SQRT1_2 } },
        ],
      },
      [0.25, 0.7, 0.75],
    ],
  ];
}

function terrain(): ShapeSpec {
  const n = 24;
  const heights: number[] = [];
  for (let z = 0; z < n; z++) for (let x = 0; x < n; x++) heights.push(0.9 * Math.sin(x * 0.35) * Math.cos(z * 0.3) + 0.9);
  return { kind: 'heightField', heights, sampleCount: n, cellSize: 0.5, originXz: { x: -6, z: -14 } };
}

async function start(): Promise<void> {
  const canvas = document.getElementById('scene') as HTMLCanvasElement;
  const params = new URLSearchParams(location.search);
  const extra = Math.max(0, Math.min(4000, Number(params.get('count') ?? '0') | 0));
  const timer = new FrameTimer();
  let firstFrameMs: number | null = null;
  let error: string | null = null;
  let renderer: Renderer | null = null;
  const movers: Mover[] = [];

  installTestHook(() => ({
    page: 'gallery',
    connected: false,
    playerId: null,
    roomId: null,
    scenario: 'gallery',
    serverTick: 0,
    renderTick: 0,
    framesRendered: timer.total,
    firstFrameMs,
    startup: { gpuReadyMs: null, welcomeMs: null },
    frameTiming: timer.summary(),
    adapter: renderer?.adapter ?? null,
    error,
    bodies: movers.map((m): HookBody => {
      const p = renderer?.store.pose(m.id) ?? [0, 0, 0, 0, 0, 0, 1];
      return { id: m.id, position: [p[0], p[1], p[2]], rotation: [p[3], p[4], p[5], p[6]] };
    }),
    characters: [],
    sensors: [],
    events: [],
    net: { rttMs: 0, snapshotsPerSecond: 0, kbpsIn: 0, interpolationDelayMs: 0, bufferDepth: 0, inputLeadTicks: 0, netMode: null, prediction: null },
    keyToMotion: null,
    camera: null,
  }));

  try {
    renderer = await Renderer.create(canvas);
  } catch (err) {
    error = (err as Error).message;
    showMessage(err instanceof WebGpuUnavailableError ? 'WebGPU is not available' : 'Renderer failed to start', error);
    return;
  }
  const r = renderer;
  r.lost.then((reason) => {
    error = `GPU device lost (${reason})`;
    showMessage('The GPU device was lost', error);
  });

  const rand = lcg(7);
  let nextId = 0;
  r.addBody(nextId++, { shape: { kind: 'box', halfExtents: { x: 14, y: 0.5, z: 14 } }, isStatic: true, position: { x: 0, y: -0.5, z: 0 }, style: { color: [0.36, 0.42, 0.33], flags: InstanceFlag.Grid } });
  r.addBody(nextId++, { shape: terrain(), isStatic: true, style: { color: [0.42, 0.5, 0.3], flags: InstanceFlag.Grid } });
  r.addBody(nextId++, {
    shape: { kind: 'mesh', positions: [0, 0, 0, 3, 0, 0, 3, 1.2, -2, 0, 1.2, -2, 0, 0, -2, 3, 0, -2], indices: [0, 1, 2, 0, 2, 3, 3, 2, 5, 3, 5, 4] },
    isStatic: true,
    position: { x: 5, y: 0, z: -5 },
    style: { color: [0.5, 0.5, 0.52] },
  });
  const sensorId = nextId++;
  r.addBody(sensorId, { shape: { kind: 'box', halfExtents: { x: 1.5, y: 1, z: 1.5 } }, isStatic: true, position: { x: -6, y: 1, z: 5 }, style: { color: [0.95, 0.85, 0.2], flags: InstanceFlag.Outline } });

  const kinds = shapes(rand);
  const total = kinds.length + extra;
  for (let i = 0; i < total; i++) {
    const [shape, color] = i < kinds.length ? kinds[i] : kinds[Math.floor(rand() * kinds.length)];
    const angle = (i / total) * Math.PI * 2;
    const radius = i < kinds.length ? 4 : 2 + rand() * 9;
    const id = nextId++;
    r.addBody(id, { shape, isStatic: false, style: { color } });
    const ax = rand() - 0.5;
    const ay = rand() - 0.5;
    const az = rand() - 0.5;
    const len = Math.sqrt(ax * ax + ay * ay + az * az) || 1;
    movers.push({ id, x: Math.cos(angle) * radius, z: Math.sin(angle) * radius, dropHeight: 3 + rand() * 5, phase: rand() * 3, spinAxis: [ax / len, ay / len, az / len] });
  }

  const camera = new OrbitCamera();
  camera.frame([-14, 0, -14], [14, 6, 14]);
  camera.radiusMetres = 15;
  camera.driftRadiansPerSecond = 0.05;
  const t0 = performance.now();
  let last = t0;
  const frame = (now: number): void => {
    if (error) return;
    const cpuStart = performance.now();
    const t = (now - t0) / 1000;
    for (const m of movers) {
      // Fall under gravity from dropHeight, bounce with decreasing height, repeat every 4 s.
      const cycle = (t + m.phase) % 4;
      const y = Math.max(0.6, m.dropHeight - 4.9 * cycle * cycle) + Math.abs(Math.sin(cycle * 6)) * Math.max(0, 1.5 - cycle) * 0.4;
      const angle = t * 1.5 + m.phase;
      const s = Math.sin(angle / 2);
      r.store.setPose(m.id, m.x, y, m.z, m.spinAxis[0] * s, m.spinAxis[1] * s, m.spinAxis[2] * s, Math.cos(angle / 2));
    }
    const lit = Math.floor(t) % 2 === 0;
    r.store.setStyle(sensorId, { emissive: lit ? 1.5 : 0 });
    r.render(camera.view((now - last) / 1000));
    last = now;
    timer.record(cpuStart, performance.now() - cpuStart);
    if (firstFrameMs === null) firstFrameMs = performance.now();
    requestAnimationFrame(frame);
  };
  requestAnimationFrame(frame);
}

start().catch((err: unknown) => {
  console.error(err);
  showMessage('The gallery failed to start', (err as Error).message);
});
