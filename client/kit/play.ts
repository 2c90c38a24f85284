// play(): a game page's whole view in one call, for pages a game writes itself. Connects with the client library,
// draws the room with the stock WebGPU renderer (a follow camera on your character, an orbit camera before it
// exists) and sends keyboard and mouse input at the tick rate. The page keeps the client for its own state and UI.
import { connect, type NetClient, type NetClientOptions } from '../../sdk/index.ts';
import { FollowCamera, OrbitCamera } from '../render/camera.ts';
import { Renderer } from '../render/renderer.ts';
import { InputController } from '../app/input-controller.ts';
import { WorldView } from '../app/world-view.ts';

/** Options of play(). */
export interface PlayOptions extends Partial<Omit<NetClientOptions, 'name'>> {
  /** WebSocket URL; default this page's server (ws(s)://host/). */
  url?: string;
  /** Display name; default a random `player-NNNN`. */
  name?: string;
  /** Lines for the page to show (joins, refusals, protocol problems); default console.log. */
  log?: (line: string) => void;
  /** The scenario's game input fields by name, read with every input sent (e.g. `() => ({ kick: keyDown ? 1 : 0 })`). */
  gameInput?: () => Readonly<Record<string, number>>;
}

/** A running game view. */
export interface PlayHandle {
  /** The connection (welcome, events, snapshots, stats, setInput is driven by the view). */
  readonly client: NetClient;
  readonly renderer: Renderer;
  /** Stops drawing and sending input, closes the connection and releases the GPU. */
  stop(): void;
}

/** Starts the view on `canvas`; rejects with the renderer's Error when WebGPU is not available. */
export async function play(canvas: HTMLCanvasElement, opts: PlayOptions = {}): Promise<PlayHandle> {
  const renderer = await Renderer.create(canvas);
  const log = opts.log ?? ((line: string) => console.log(line));
  const url = opts.url ?? `${location.protocol === 'https:' ? 'wss' : 'ws'}://${location.host}/`;
  const { url: _url, log: _log, gameInput, ...clientOptions } = opts;
  const client = connect(url, { ...clientOptions, name: opts.name ?? `player-${Math.floor(Math.random() * 9000 + 1000)}` });
  const world = new WorldView(renderer, log);
  const input = new InputController(canvas);
  const follow = new FollowCamera();
  const orbit = new OrbitCamera();
  let rafId = 0;
  let inputTimer: ReturnType<typeof setInterval> | null = null;
  let lastFrameMs: number | null = null;
  let stopped = false;

  const frame = (rafMs: number): void => {
    if (stopped) return;
    rafId = requestAnimationFrame(frame);
    const dtSeconds = lastFrameMs === null ? 0 : Math.max(0, (rafMs - lastFrameMs) / 1000);
    lastFrameMs = rafMs;
    const f = client.sample();
    world.apply(f.view, f.renderTick);
    const mine = f.view?.characters.find((c) => c.playerId === client.playerId) ?? null;
    input.captureOnClick = mine !== null;
    const camera = mine ? follow.view([mine.position.x, mine.position.y, mine.position.z], input.yawRadians, input.pitchRadians, dtSeconds, world.occluders) : orbit.view(dtSeconds);
    renderer.render(camera);
  };

  client.on('welcome', (w) => {
    world.reset(w.staticBodies, w.dynamicBodies);
    const b = w.scenario.bounds;
    orbit.frame([b.min.x, b.min.y, b.min.z], [b.max.x, b.max.y, b.max.z]);
    log(`joined ${w.roomId} (${w.scenario.name}) as #${w.playerId}`);
    input.attach();
    const send = (): void => client.setInput(gameInput ? { ...input.sample(), ...gameInput() } : input.sample());
    if (inputTimer === null) inputTimer = setInterval(() => client.state !== 'closed' && send(), 1000 / w.tickRateHz);
    if (rafId === 0) rafId = requestAnimationFrame(frame);
  });
  client.on('snapshot', (s) => world.addDescriptors(s.tick, s.descriptors));
  client.on('events', (events) => world.queueEvents(events));
  client.on('serverError', (e) => log(`server refused: ${e.code}: ${e.message}`));
  client.on('closed', (c) => log(`disconnected: ${c.reason}${c.detail ? ` (${c.detail})` : ''}`));

  return {
    client,
    renderer,
    stop() {
      if (stopped) return;
      stopped = true;
      cancelAnimationFrame(rafId);
      if (inputTimer !== null) clearInterval(inputTimer);
      input.detach();
      client.close();
      renderer.destroy();
    },
  };
}
