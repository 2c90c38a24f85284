// The per-frame loop of a joined room: input sampled → predicted (own simulation) or interpolated view → world →
// camera → render; input also at 60 Hz between frames; HUD and the test hook's state. Owns the frame timer and the
// cameras; the session owns the network.
import { FollowCamera, OrbitCamera } from '../render/camera.ts';
import type { CameraView } from '../render/renderer.ts';
import type { Renderer } from '../render/renderer.ts';
import { FrameTimer } from './frame-timer.ts';
import { KeyToMotionMeter } from './motion-meter.ts';
import type { Hud } from './hud.ts';
import type { InputController } from './input-controller.ts';
import { NetHistory } from './net-history.ts';
import { contentBox } from './scene-extent.ts';
import type { NetSession, SessionWelcome } from './session-types.ts';
import type { SnapshotView } from '../../shared/protocol/snapshot-frame.ts';
import type { BodyDescriptor } from '../../shared/sim/types.ts';
import type { WorldView } from './world-view.ts';
import type { Decorations } from './decorations.ts';
import type { NameTags } from './name-tags.ts';

/** What the loop reports to the page each frame (and the test hook reads). */
export interface LoopState {
  framesRendered: number;
  firstFrameMs: number | null;
  renderTick: number;
  bufferDepth: number;
  delayMs: number;
  /** The interpolated view drawn last (the hook copies bodies and characters out of it only when read). */
  view: SnapshotView | null;
  /** True while the follow camera tracks our character. */
  following: boolean;
  /** The last frame's camera and canvas size. */
  camera: (CameraView & { widthPx: number; heightPx: number }) | null;
}

/** Runs frames until stop(). */
export class GameLoop {
  readonly timer = new FrameTimer();
  readonly history: NetHistory;
  /** Key → own character moving on screen. */
  readonly motion = new KeyToMotionMeter();
  readonly state: LoopState = { framesRendered: 0, firstFrameMs: null, renderTick: 0, bufferDepth: 0, delayMs: 0, view: null, following: false, camera: null };
  /** Force the orbit camera even when we have a character (V toggles it). */
  orbitOnly = false;

  private readonly renderer: Renderer;
  private readonly world: WorldView;
  private readonly decorations: Decorations | null;
  private readonly tags: NameTags | null;
  /** Per-frame page extras (the scenario's objective). */
  private readonly onFrame: ((view: SnapshotView | null) => void) | null;
  private readonly session: NetSession;
  private readonly input: InputController;
  private readonly hud: Hud;
  private readonly welcome: SessionWelcome;
  private readonly follow = new FollowCamera();
  private readonly orbit = new OrbitCamera();
  /** Whether the orbit camera has been fitted to the scene's content since it was last switched to. */
  private orbitFitted = false;
  private rafId = 0;
  private inputTimer: ReturnType<typeof setInterval> | null = null;
  private lastFrameMs: number | null = null;
  private stopped = false;
  private readonly onFatal: (err: Error) => void;

  constructor(parts: { renderer: Renderer; world: WorldView; decorations?: Decorations; tags?: NameTags; onFrame?: (view: SnapshotView | null) => void; session: NetSession; input: InputController; hud: Hud; welcome: SessionWelcome; onFatal: (err: Error) => void }) {
    this.renderer = parts.renderer;
    this.decorations = parts.decorations ?? null;
    this.tags = parts.tags ?? null;
    this.onFrame = parts.onFrame ?? null;
    this.world = parts.world;
    this.session = parts.session;
    this.input = parts.input;
    this.hud = parts.hud;
    this.welcome = parts.welcome;
    this.onFatal = parts.onFatal;
    this.history = new NetHistory(parts.welcome.tickRateHz);
    const b = parts.welcome.scenario.bounds;
    this.orbit.frame([b.min.x, b.min.y, b.min.z], [b.max.x, b.max.y, b.max.z]);
  }

  /** Starts rendering and sending input at the tick rate. */
  start(): void {
    // A movement key is handed to the library at once (not at the next 60 Hz sample), and starts a latency measurement.
    this.input.onMoveKeyDown = (atMs) => {
      this.session.setInput(this.input.sample(atMs));
      this.motion.keyDown(atMs, this.state.framesRendered, this.session.newestInputTick + 1);
    };
    this.rafId = requestAnimationFrame((t) => this.frame(t));
    const intervalMs = 1000 / this.welcome.tickRateHz;
    this.inputTimer = setInterval(() => this.session.setInput(this.input.sample()), intervalMs);
  }

  /** Stops the loop (the last frame stays on screen). */
  stop(): void {
    this.stopped = true;
    this.input.onMoveKeyDown = null;
    cancelAnimationFrame(this.rafId);
    if (this.inputTimer !== null) clearInterval(this.inputTimer);
    this.inputTimer = null;
  }

  /** Turns the orbit camera by a drag (spectating). */
  orbitDrag(dxPx: number, dyPx: number): void {
    this.orbit.drag(dxPx, dyPx);
  }

  /** Zooms the orbit camera. */
  orbitZoom(deltaY: number): void {
    this.orbit.zoom(deltaY);
  }

  private frame(rafMs: number): void {
    if (this.stopped) return;
    this.rafId = requestAnimationFrame((t) => this.frame(t));
    const cpuStart = performance.now();
    const dtSeconds = this.lastFrameMs === null ? 0 : Math.max(0, (rafMs - this.lastFrameMs) / 1000);
    this.lastFrameMs = rafMs;
    try {
      this.draw(cpuStart, dtSeconds);
    } catch (err) {
      this.stop();
      this.onFatal(err as Error);
      return;
    }
    this.timer.record(cpuStart, performance.now() - cpuStart);
  }

  private draw(nowMs: number, dt: number): void {
    // Input is sampled at the frame: a predicted frame fixes and simulates the new command's tick before drawing.
    this.session.setInput(this.input.sample(nowMs));
    const predicted = this.session.predicted();
    const f = predicted ? { view: predicted.view, renderTick: predicted.tick, bufferDepth: 0, delayMs: 0 } : this.session.frame(nowMs);
    if (predicted) this.describeSpawns(predicted.view, predicted.tick);
    this.world.apply(f.view, f.renderTick);
    this.decorations?.update(f.view, nowMs);
    this.history.recordBufferDepth(nowMs, f.bufferDepth);
    const s = this.state;
    s.renderTick = f.renderTick;
    s.bufferDepth = f.bufferDepth;
    s.delayMs = f.delayMs;
    s.view = f.view;
    const mine = f.view?.characters.find((c) => c.playerId === this.welcome.playerId) ?? null;
    let camera: CameraView;
    if (mine && !this.orbitOnly) {
      camera = this.follow.view([mine.position.x, mine.position.y, mine.position.z], this.input.yawRadians, this.input.pitchRadians, dt, this.world.occluders);
      s.following = true;
      this.orbitFitted = false;
    } else {
      if (s.following) this.follow.reset();
      if (!this.orbitFitted && f.view) {
        const box = contentBox(this.world.staticDescriptors(), f.view, this.welcome.scenario.bounds);
        this.orbit.frame(box.min, box.max);
        this.orbitFitted = true;
      }
      camera = this.orbit.view(dt);
      s.following = false;
    }
    this.input.captureOnClick = s.following;
    const stats = this.renderer.render(camera);
    s.camera = { ...camera, widthPx: stats.widthPx, heightPx: stats.heightPx };
    this.tags?.update(f.view, camera, stats.widthPx, stats.heightPx);
    this.onFrame?.(f.view);
    s.framesRendered++;
    if (s.firstFrameMs === null && f.view) s.firstFrameMs = performance.now();
    const confirmed = predicted ? (this.session.prediction?.confirmedTick ?? predicted.tick) : this.session.serverTick;
    this.motion.frameDrawn(performance.now(), s.framesRendered, f.renderTick, f.renderTick - confirmed, mine ? [mine.position.x, mine.position.y, mine.position.z] : null);
    const timing = this.timer.summary();
    const prediction = this.session.prediction;
    this.hud.refresh(nowMs, {
      netMode: prediction ? prediction.mode : this.welcome.netMode,
      prediction,
      room: `${this.welcome.roomId} (${this.welcome.scenario.name})`,
      playerId: mine ? this.welcome.playerId : null,
      serverTick: this.session.serverTick,
      rttMs: this.session.rttMs,
      inputLeadTicks: this.session.inputLeadTicks,
      roomPace: this.session.roomPace,
      snapshotsPerSecond: this.history.snapshotsPerSecond(nowMs),
      kbpsIn: prediction ? this.session.kbpsIn : this.history.kbpsIn(nowMs),
      interpolationDelayMs: f.delayMs,
      bufferDepth: f.bufferDepth,
      bodies: stats.instances,
      fps: timing.fps,
      frameMs: timing.meanCpuMs,
    }, this.history);
  }

  /** Bodies the own simulation spawned that the world view has not met: describe them from the session. */
  private describeSpawns(view: SnapshotView, tick: number): void {
    let fresh: BodyDescriptor[] | null = null;
    for (const id of view.ids) {
      if (this.world.descriptor(id)) continue;
      const d = this.session.descriptor(id);
      if (d) (fresh ??= []).push(d);
    }
    if (fresh) this.world.addDescriptors(tick, fresh);
  }
}
