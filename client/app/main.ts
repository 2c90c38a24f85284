// The page's entry point: starts WebGPU, shows the start screen (or joins ?room=ID directly), connects, and runs the
// game loop; every failure ends in a clear message (no WebGPU, server unreachable, refused, closed).
import { WebGpuUnavailableError } from '../render/gpu-context.ts';
import { Renderer } from '../render/renderer.ts';
import { GameLoop } from './game-loop.ts';
import { Hud } from './hud.ts';
import { InputController } from './input-controller.ts';
import { closedMessage } from './closed-messages.ts';
import { hideMessage, showMessage, type MessageAction } from './overlay.ts';
import { openSession } from './session.ts';
import type { NetSession, SessionWelcome } from './session-types.ts';
import { fetchLobby, showStartScreen } from './start-screen.ts';
import { installTestHook, type HookBody, type TaosState } from './test-hook.ts';
import type { SnapshotView } from '../../shared/protocol/snapshot-frame.ts';
import { WorldView } from './world-view.ts';
import { Decorations } from './decorations.ts';
import { NameTags } from './name-tags.ts';
import { COURSE_SCENARIO, CourseObjective, ObjectivePanel, objectiveLines } from './course-objective.ts';

const byId = <T extends HTMLElement>(id: string): T => {
  const e = document.getElementById(id);
  if (!e) throw new Error(`page is missing #${id}`);
  return e as T;
};

/** Page-wide state the test hook reads. */
const page = {
  phase: 'start' as string,
  connected: false,
  welcome: null as SessionWelcome | null,
  error: null as string | null,
  renderer: null as Renderer | null,
  session: null as NetSession | null,
  loop: null as GameLoop | null,
  world: null as WorldView | null,
  hud: null as Hud | null,
  gpuReadyMs: null as number | null,
  welcomeMs: null as number | null,
};

function hookState(): TaosState {
  const loop = page.loop;
  const s = loop?.state;
  const now = performance.now();
  return {
    page: page.phase,
    connected: page.connected,
    playerId: page.welcome?.playerId ?? null,
    roomId: page.welcome?.roomId ?? null,
    scenario: page.welcome?.scenario.name ?? null,
    serverTick: page.session?.serverTick ?? 0,
    renderTick: s?.renderTick ?? 0,
    framesRendered: s?.framesRendered ?? 0,
    firstFrameMs: s?.firstFrameMs ?? null,
    startup: { gpuReadyMs: page.gpuReadyMs, welcomeMs: page.welcomeMs },
    frameTiming: loop ? loop.timer.summary() : { frames: 0, fps: 0, meanIntervalMs: 0, p50IntervalMs: 0, p95IntervalMs: 0, meanCpuMs: 0, p95CpuMs: 0 },
    adapter: page.renderer?.adapter ?? null,
    error: page.error,
    bodies: s?.view ? hookBodies(s.view) : [],
    characters: s?.view ? s.view.characters.map((c) => ({ playerId: c.playerId, bodyId: c.bodyId, position: [c.position.x, c.position.y, c.position.z] as [number, number, number] })) : [],
    sensors: page.world?.sensors() ?? [],
    events: page.hud?.feedLines() ?? [],
    net: {
      rttMs: page.session?.rttMs ?? 0,
      snapshotsPerSecond: loop ? loop.history.snapshotsPerSecond(now) : 0,
      kbpsIn: loop ? loop.history.kbpsIn(now) : 0,
      interpolationDelayMs: s?.delayMs ?? 0,
      bufferDepth: s?.bufferDepth ?? 0,
      inputLeadTicks: page.session?.inputLeadTicks ?? 0,
      netMode: page.welcome?.netMode ?? null,
      prediction: page.session?.prediction ?? null,
    },
    keyToMotion: loop?.motion.last ? { ...loop.motion.last, count: loop.motion.count } : null,
    camera: s?.camera ? { ...s.camera, eye: [...s.camera.eye], target: [...s.camera.target] } : null,
  };
}

function hookBodies(v: SnapshotView): HookBody[] {
  const out: HookBody[] = [];
  for (let i = 0; i < v.ids.length; i++) {
    out.push({ id: v.ids[i], position: [v.positions[i * 3], v.positions[i * 3 + 1], v.positions[i * 3 + 2]], rotation: [v.rotations[i * 4], v.rotations[i * 4 + 1], v.rotations[i * 4 + 2], v.rotations[i * 4 + 3]] });
  }
  return out;
}

function fail(title: string, detail: string, actions: readonly MessageAction[] = [reload, backToRooms]): void {
  page.phase = 'error';
  page.error = `${title}: ${detail}`;
  showMessage(title, detail, 'error', actions);
}

const reload: MessageAction = { label: 'Try again', run: () => location.reload() };
// The lobby: the page without ?room=, keeping the other parameters (name, hud).
const backToRooms: MessageAction = {
  label: 'Back to rooms',
  run: () => {
    const url = new URL(location.href);
    url.searchParams.delete('room');
    location.assign(url.href);
  },
};

async function boot(): Promise<void> {
  installTestHook(hookState);
  const canvas = byId<HTMLCanvasElement>('scene');
  try {
    page.renderer = await Renderer.create(canvas);
    page.gpuReadyMs = performance.now();
  } catch (err) {
    if (err instanceof WebGpuUnavailableError) fail('WebGPU is not available', err.message, [reload]);
    else fail('The renderer failed to start', (err as Error).message, [reload]);
    return;
  }
  page.renderer.lost.then((reason) => {
    if (page.phase !== 'closed') fail('The GPU device was lost', `${reason}. Reload the page to start again.`);
    page.loop?.stop();
  });

  const params = new URLSearchParams(location.search);
  // ?room=ID joins that room directly; a bare ?room= joins the default room directly.
  let room = params.has('room') ? params.get('room') || null : null;
  if (!params.has('room')) {
    let lobby;
    try {
      lobby = await fetchLobby(location.origin);
    } catch (err) {
      fail('Server unreachable', (err as Error).message, [reload]);
      return;
    }
    room = (await showStartScreen(byId('start'), lobby)).room;
  }
  join(room, params.get('name') ?? `player-${Math.floor(Math.random() * 9000 + 1000)}`);
}

function join(room: string | null, name: string): void {
  const renderer = page.renderer!;
  page.phase = 'connecting';
  showMessage('Connecting…', room ? `Joining room ${room}` : 'Joining the default room', 'info');
  const hud = new Hud(byId('hud'), byId('feed'));
  page.hud = hud;
  const world = new WorldView(renderer, (line) => hud.log(line));
  page.world = world;
  const decorations = new Decorations(renderer, world);
  let tags: NameTags | null = null;
  let objective: CourseObjective | null = null;
  const objectivePanel = new ObjectivePanel(byId('objective'));
  world.onEvent = (e, removed) => {
    decorations.onEvent(e, removed);
    tags?.onEvent(e);
    objective?.onEvent(e);
  };
  const input = new InputController(byId('scene'));
  const wsUrl = `${location.protocol === 'https:' ? 'wss' : 'ws'}://${location.host}/`;

  // ?inputDelay=N: predicted play's input delay in ticks instead of the room's (a bad value is refused like a bad name).
  const inputDelay = new URLSearchParams(location.search).get('inputDelay');
  page.session = openSession(wsUrl, { name, room, inputDelayTicks: inputDelay === null ? undefined : Number(inputDelay) }, {
    onWelcome(welcome) {
      page.welcomeMs ??= performance.now();
      page.welcome = welcome;
      page.connected = true;
      page.phase = 'playing';
      page.error = null;
      hideMessage();
      decorations.clear();
      tags?.clear();
      tags = new NameTags(byId('tags'), welcome.playerId);
      void tags.fetchNames(welcome.roomId);
      world.reset(welcome.staticBodies, welcome.dynamicBodies);
      objective = welcome.scenario.name === COURSE_SCENARIO ? new CourseObjective(world.staticDescriptors(), (id) => world.descriptor(id)) : null;
      objectivePanel.show([]);
      page.loop?.stop();
      const crosshair = byId('crosshair');
      const onFrame = (view: SnapshotView | null): void => {
        objectivePanel.show(objective ? objectiveLines(objective.state(view)) : []);
        // Aiming means something only from the follow camera.
        const aiming = page.loop?.state.following ?? false;
        if (crosshair.hidden === aiming) crosshair.hidden = !aiming;
      };
      const loop = new GameLoop({ renderer, world, decorations, tags, onFrame, session: page.session!, input, hud, welcome, onFatal: (err) => fail('Rendering failed', err.message) });
      page.loop = loop;
      // ?hud=0 starts with the HUD and help hidden (clean screenshots); H toggles them.
      const showHud = new URLSearchParams(location.search).get('hud') !== '0';
      hud.visible = showHud;
      byId('help').hidden = !showHud;
      hud.log(`joined ${welcome.roomId} (${welcome.scenario.name}) as #${welcome.playerId}`);
      input.attach();
      loop.start();
    },
    onSnapshot(tick, sizeBytes, descriptors) {
      const now = performance.now();
      page.loop?.history.recordSnapshot(now, tick);
      page.loop?.history.recordBytes(now, sizeBytes);
      world.addDescriptors(tick, descriptors);
    },
    onEvents(events) {
      world.queueEvents(events);
    },
    onReconnecting(attempt, reason, serverRestarting) {
      page.connected = false;
      page.phase = 'connecting';
      if (serverRestarting) showMessage('Server restarted, rejoining', `The server went away and is coming back: rejoining (attempt ${attempt})…`, 'info');
      else showMessage('Connection lost', `${reason}\nReconnecting (attempt ${attempt})…`, 'info');
    },
    onNotice(line) {
      console.warn(line);
      hud.log(line);
    },
    onClosed(reason, detail) {
      page.connected = false;
      page.loop?.stop();
      input.detach();
      const m = closedMessage(reason);
      fail(m.title, `${detail}\n${m.hint}`, m.retry ? [reload, backToRooms] : [backToRooms]);
      page.phase = 'closed';
    },
  });
  bindKeys(input);
}

function bindKeys(input: InputController): void {
  window.addEventListener('keydown', (e) => {
    if (e.code === 'KeyH') {
      const hud = byId('hud');
      const on = hud.hidden;
      if (page.hud) page.hud.visible = on;
      byId('help').hidden = !on;
    } else if (e.code === 'KeyV' && page.loop) {
      page.loop.orbitOnly = !page.loop.orbitOnly;
    }
  });
  const canvas = byId<HTMLCanvasElement>('scene');
  // Spectating (orbit camera): drag to turn, wheel to zoom.
  canvas.addEventListener('mousemove', (e) => {
    if (page.loop && !page.loop.state.following && (e.buttons & 1) !== 0 && !input.pointerLocked) page.loop.orbitDrag(e.movementX, e.movementY);
  });
  canvas.addEventListener('wheel', (e) => page.loop?.orbitZoom(e.deltaY), { passive: true });
  window.addEventListener('pagehide', () => page.session?.close());
}

boot().catch((err: unknown) => {
  console.error(err);
  fail('The client failed to start', (err as Error).message);
});
