// The replay viewer page (replay.html): opens a .taoslog from the file picker, a drop or the log `serve --replay`
// serves, loads the physics chunk, checks the log's recorded hashes against this browser, then plays it with the
// stock renderer: play/pause, scrub, speed, and a followed player. Test hook: `window.__taosReplay` (read-only).
import { FollowCamera, OrbitCamera } from '../render/camera.ts';
import { WebGpuUnavailableError } from '../render/gpu-context.ts';
import type { CameraView, Renderer as RendererType } from '../render/renderer.ts';
import { Renderer } from '../render/renderer.ts';
import type { ReplayPlayer, ReplayVerification } from '../physics/replay-player.ts';
import { FrameTimer } from './frame-timer.ts';
import { hideMessage, showMessage } from './overlay.ts';
import { loadPhysics } from './physics-loader.ts';
import { bindReplayControls, type ReplayControls } from './replay-controls.ts';
import { WorldView } from './world-view.ts';

/** Where `serve --replay FILE` serves its log. */
const SERVED_LOG_PATH = '/replay.taoslog';
/** The most ticks one frame steps during playback (a slow frame catches up over several). */
const MAX_TICKS_PER_FRAME = 32;

const page = {
  phase: 'empty' as 'empty' | 'loading' | 'verifying' | 'ready' | 'error',
  source: null as string | null,
  error: null as string | null,
  renderer: null as RendererType | null,
  world: null as WorldView | null,
  player: null as ReplayPlayer | null,
  verification: null as ReplayVerification | null,
  verifiedTicks: 0,
  playing: false,
  speed: 1,
  follow: null as number | null,
  accumulatorTicks: 0,
  framesRendered: 0,
  /** The tick whose state the last rendered frame showed. */
  renderedTick: -1,
  lastFrameMs: null as number | null,
  /** Bumped on each open, so an older load that finishes late is dropped. */
  generation: 0,
};
const timer = new FrameTimer();
const orbit = new OrbitCamera();
const followCam = new FollowCamera();
let controls: ReplayControls;

function hookState(): Record<string, unknown> {
  const p = page.player;
  const store = page.renderer?.store;
  const drawn = p && store && page.phase === 'ready' ? p.frame().ids : new Uint32Array(0);
  return {
    phase: page.phase,
    source: page.source,
    error: page.error,
    scenario: p?.header.scenario ?? null,
    tick: p && page.phase === 'ready' ? p.tick : 0,
    lastTick: p?.lastTick ?? 0,
    totalTicks: p?.totalTicks ?? 0,
    verifiedTicks: page.verifiedTicks,
    verification: page.verification ? { ...page.verification } : null,
    stateHash: p && page.phase === 'ready' ? p.stateHash() : null,
    renderedTick: page.renderedTick,
    framesRendered: page.framesRendered,
    playing: page.playing,
    speed: page.speed,
    follow: page.follow,
    drawn: [...drawn].map((id) => ({ id, pose: store?.pose(id) ? [...store.pose(id)!] : null })),
  };
}

function fail(title: string, detail: string): void {
  page.phase = 'error';
  page.error = `${title}: ${detail}`;
  page.playing = false;
  controls?.setStatus(`${title}: ${detail}`, 'bad');
  showMessage(title, detail, 'error');
}

/** Opens a log's bytes: loads the physics chunk, builds the scenario, checks every recorded hash, shows tick 0. */
async function openLog(bytes: Uint8Array, source: string): Promise<void> {
  const generation = ++page.generation;
  page.player?.destroy();
  page.player = null;
  page.verification = null;
  page.verifiedTicks = 0;
  page.playing = false;
  page.error = null;
  page.source = source;
  page.phase = 'loading';
  page.renderedTick = -1;
  if (page.renderer) hideMessage();
  controls.setLog(source, null);
  controls.setStatus('Loading the physics engine…', null);
  let player: ReplayPlayer;
  try {
    const physics = await loadPhysics();
    player = await physics.ReplayPlayer.open(bytes, source);
  } catch (err) {
    if (generation === page.generation) fail('Cannot open this log', (err as Error).message);
    return;
  }
  if (generation !== page.generation) {
    player.destroy();
    return;
  }
  page.player = player;
  page.phase = 'verifying';
  controls.setLog(source, player);
  let verification: ReplayVerification;
  try {
    verification = await player.verify((tick) => {
      page.verifiedTicks = tick;
      controls.setStatus(`Checking recorded hashes… tick ${tick} / ${player.totalTicks}`, null);
    });
  } catch (err) {
    if (generation === page.generation) fail('Cannot play this log', (err as Error).message);
    return;
  }
  if (generation !== page.generation) return;
  page.verification = verification;
  page.verifiedTicks = player.lastTick;
  controls.setStatus(verificationText(verification, player), verification.firstMismatchTick === null && !verification.failure ? 'good' : 'bad');
  const { min, max } = player.bounds;
  orbit.frame([min.x, min.y, min.z], [max.x, max.y, max.z]);
  page.follow = player.playersInLog()[0]?.playerId ?? null;
  controls.setFollow(page.follow);
  seekTo(0, true);
  page.phase = 'ready';
  controls.setPlaying(false);
}

function verificationText(v: ReplayVerification, player: ReplayPlayer): string {
  const log = player.logStatus === 'complete' ? '' : ` (the log is ${player.logStatus})`;
  if (v.failure) return `Playback stops at tick ${player.lastTick}: ${v.failure}${log}`;
  if (v.hashesChecked === 0) return `The log records no hashes to check${log}`;
  if (v.firstMismatchTick === null) return `All ${v.hashesChecked} recorded hashes match this browser${log}`;
  return `Recorded hashes stop matching this browser at tick ${v.firstMismatchTick} (recorded ${v.expected}, this browser ${v.actual})${log}`;
}

/** Moves playback to `tick`; redraws the world from the simulation after a jump, applies events after a step. */
function seekTo(tick: number, redraw = false): void {
  const player = page.player;
  const world = page.world;
  if (!player) return;
  const { jumped, events } = player.seek(tick);
  controls.setTick(player.tick, player.lastTick);
  // Without WebGPU there is nothing to draw: the log is still checked and the scrubber still moves the simulation.
  if (!world) return;
  if (jumped || redraw) {
    const all = player.descriptors();
    world.reset(
      all.filter((d) => d.motion === 'static'),
      all.filter((d) => d.motion !== 'static'),
    );
  } else {
    world.queueEvents(events);
    const fresh = [];
    for (const e of events) {
      const id = e.type === 'bodySpawned' || e.type === 'playerJoined' ? e.bodyId : undefined;
      const d = id === undefined ? undefined : player.bodyDescriptor(id);
      if (d) fresh.push(d);
    }
    world.addDescriptors(player.tick, fresh);
  }
}

function frame(nowMs: number): void {
  requestAnimationFrame(frame);
  const renderer = page.renderer;
  const world = page.world;
  if (!renderer || !world) return;
  const cpuStart = performance.now();
  const dtSeconds = page.lastFrameMs === null ? 0 : Math.max(0, (nowMs - page.lastFrameMs) / 1000);
  page.lastFrameMs = nowMs;
  const player = page.phase === 'ready' ? page.player : null;
  let camera: CameraView;
  try {
    if (player && page.playing) {
      page.accumulatorTicks += dtSeconds * player.header.tickRateHz * page.speed;
      const steps = Math.min(MAX_TICKS_PER_FRAME, Math.floor(page.accumulatorTicks));
      page.accumulatorTicks = Math.min(page.accumulatorTicks - steps, MAX_TICKS_PER_FRAME);
      if (steps > 0) seekTo(Math.min(player.lastTick, player.tick + steps));
      if (player.tick >= player.lastTick) setPlaying(false);
    }
    const view = player ? player.frame() : null;
    if (view) world.apply(view, view.tick);
    const followed = view && page.follow !== null ? view.characters.find((c) => c.playerId === page.follow) : undefined;
    camera = followed ? followCam.view([followed.position.x, followed.position.y, followed.position.z], followed.yaw, followed.pitch, dtSeconds, world.occluders) : orbit.view(dtSeconds);
    renderer.render(camera);
    page.renderedTick = view ? view.tick : -1;
    page.framesRendered++;
  } catch (err) {
    fail('Playback failed', (err as Error).message);
    return;
  }
  timer.record(cpuStart, performance.now() - cpuStart);
}

function setPlaying(on: boolean): void {
  const player = page.player;
  if (on && player && player.tick >= player.lastTick) seekTo(0);
  page.playing = on && page.phase === 'ready';
  page.accumulatorTicks = 0;
  controls.setPlaying(page.playing);
}

async function openServedLog(): Promise<void> {
  let res: Response;
  try {
    res = await fetch(SERVED_LOG_PATH);
  } catch {
    return; // no server behind this page (opened from disk): the picker still works
  }
  if (!res.ok) return;
  const name = res.headers.get('x-taos-log-name') ?? 'served log';
  await openLog(new Uint8Array(await res.arrayBuffer()), name);
}

async function boot(): Promise<void> {
  Object.defineProperty(globalThis, '__taosReplay', { get: () => Object.freeze(hookState()), configurable: true });
  controls = bindReplayControls({
    open: (bytes, name) => void openLog(bytes, name),
    togglePlay: () => setPlaying(!page.playing),
    scrub: (tick) => {
      if (page.phase === 'ready') seekTo(tick);
    },
    stepBy: (ticks) => {
      if (page.phase === 'ready' && page.player) seekTo(page.player.tick + ticks);
    },
    speed: (x) => {
      page.speed = x;
    },
    follow: (playerId) => {
      page.follow = playerId;
      followCam.reset();
    },
    orbitDrag: (dx, dy) => orbit.drag(dx, dy),
    orbitZoom: (dy) => orbit.zoom(dy),
  });
  const canvas = document.getElementById('scene') as HTMLCanvasElement;
  try {
    page.renderer = await Renderer.create(canvas);
  } catch (err) {
    // Checking a log's hashes needs only WASM: say what is missing and keep the rest of the viewer working.
    const title = err instanceof WebGpuUnavailableError ? 'WebGPU is not available' : 'The renderer failed to start';
    showMessage(title, `${(err as Error).message}\nLogs can still be opened and their recorded hashes checked; nothing is drawn.`, 'info');
    await openServedLog();
    return;
  }
  page.renderer.lost.then((reason) => fail('The GPU device was lost', `${reason}. Reload the page to start again.`));
  page.world = new WorldView(page.renderer, () => undefined);
  orbit.frame([-20, 0, -20], [20, 8, 20]);
  requestAnimationFrame(frame);
  await openServedLog();
}

boot().catch((err: unknown) => {
  console.error(err);
  fail('The replay viewer failed to start', (err as Error).message);
});
