// The page's network session: a thin adapter over the client library (sdk's NetClient) that maps its
// events, interpolated frames and predicted frames onto what the page uses (session-types.ts). In a room whose
// welcome says predict, the library asks for the room's simulation: only then is the physics chunk loaded.
import { connect, type NetClient, type PredictOptions } from '../../sdk/index.ts';
import type { InputCommand } from '../../shared/sim/input.ts';
import { viewFromBodyStates } from './body-view.ts';
import { loadPhysics } from './physics-loader.ts';
import type { NetSession, SessionFrame, SessionHandlers } from './session-types.ts';

/** Predicted play for the page: the room's simulation comes from the physics chunk, fetched on first use. */
function predictOptions(inputDelayTicks: number | undefined): PredictOptions {
  return {
    async createSimulation(setup) {
      const physics = await loadPhysics();
      return physics.Simulation.create({ scenario: physics.getScenario(setup.scenario), params: setup.params, seed: setup.seed });
    },
    ...(inputDelayTicks === undefined ? {} : { inputDelayTicks }),
  };
}

/** Connects to `wsUrl` and reports through `handlers`; the returned session lives until close() or onClosed. */
/** `inputDelayTicks`: predicted play's input delay instead of the room's (undefined: the room's). */
export function openSession(wsUrl: string, opts: { name: string; room: string | null; inputDelayTicks?: number }, handlers: SessionHandlers): NetSession {
  let client: NetClient;
  try {
    client = connect(wsUrl, { name: opts.name, room: opts.room, predict: predictOptions(opts.inputDelayTicks) });
  } catch (err) {
    // Bad name or room id: report it like any other refusal.
    const message = (err as Error).message;
    queueMicrotask(() => handlers.onClosed('bad-request', message));
    return closedSession();
  }
  client.on('welcome', (w) =>
    handlers.onWelcome({
      playerId: w.playerId,
      roomId: w.roomId,
      tick: w.tick,
      tickRateHz: w.tickRateHz,
      snapshotRateHz: w.snapshotRateHz,
      scenario: w.scenario,
      staticBodies: w.staticBodies,
      dynamicBodies: w.dynamicBodies,
      netMode: w.netMode,
    }),
  );
  client.on('snapshot', (s) => handlers.onSnapshot(s.tick, s.sizeBytes, s.descriptors));
  client.on('events', (events) => handlers.onEvents(events));
  client.on('reconnecting', (r) => handlers.onReconnecting(r.attempt, r.reason, r.serverRestarting));
  client.on('closed', (c) => handlers.onClosed(c.reason, c.detail));
  client.on('serverError', (e) => handlers.onNotice(`server refused: ${e.code}: ${e.message}`));
  client.on('protocolError', (m) => handlers.onNotice(`protocol problem: ${m}`));

  return {
    get serverTick() {
      const t = client.serverTick();
      return t === null ? 0 : Math.floor(t);
    },
    get rttMs() {
      return client.stats().rttMs;
    },
    get inputLeadTicks() {
      return client.stats().leadTicks;
    },
    get newestInputTick() {
      return client.stats().newestInputTick;
    },
    get roomPace() {
      return client.stats().roomPace;
    },
    frame(nowMs: number): SessionFrame {
      const f = client.sample(nowMs);
      return { view: f.view, renderTick: f.renderTick, bufferDepth: f.bufferDepth, delayMs: f.delayMs };
    },
    predicted() {
      const p = client.predicted();
      return p ? { tick: p.tick, view: viewFromBodyStates(p.tick, p.bodies, p.characters) } : null;
    },
    descriptor(id: number) {
      return client.descriptor(id);
    },
    get prediction() {
      return client.stats().prediction;
    },
    get kbpsIn() {
      return client.stats().kbpsIn;
    },
    setInput(cmd: InputCommand) {
      if (client.state !== 'closed') client.setInput(cmd);
    },
    close() {
      client.close();
    },
  };
}

function closedSession(): NetSession {
  return {
    serverTick: 0,
    rttMs: null,
    inputLeadTicks: null,
    newestInputTick: -1,
    roomPace: null,
    frame: () => ({ view: null, renderTick: 0, bufferDepth: 0, delayMs: 0 }),
    predicted: () => null,
    descriptor: () => undefined,
    prediction: null,
    kbpsIn: 0,
    setInput: () => undefined,
    close: () => undefined,
  };
}
