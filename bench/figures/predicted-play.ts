// Predicted play (issue 10): the server and client-library players in this process over an in-memory link with
// 50 ms each way (100 ms RTT) on the real clock. Key → own character moving on the next drawn frame (60 Hz) in
// predict mode vs snapshot mode; bytes per predicting client with 4 and 16 players on cubes-901 and
// character-course; rollback depth and re-simulation time per frame for every scenario; desyncs per hour of play.
import { nodePredictOptions } from '../../cli/predict-options.ts';
import { startBots } from '../../cli/bots.ts';
import { listScenarios } from '../../scenarios/index.ts';
import { connect, MemoryNetwork, RealClock, type NetClient, type PredictionStats } from '../../sdk/index.ts';
import { GameServer } from '../../server/game-server.ts';
import { silentLogger } from '../../server/logger.ts';
import { memoryPeerConnection } from '../../server/memory-peer.ts';
import { createMetrics } from '../../server/metrics.ts';
import { createRoomFactory } from '../../server/room-factory.ts';
import { registryScenarios } from '../../server/start-server.ts';
import { Prng } from '../../shared/sim/prng.ts';
import { commandYawRadians } from '../../shared/sim/controls.ts';
import type { InputCommand } from '../../shared/sim/input.ts';
import type { CharacterState } from '../../shared/sim/types.ts';
import type { FigureImpl, FigureOutput } from '../lib/figure.ts';
import { round, summarize } from '../lib/stats.ts';

const URL = 'ws://bench.memory/';
const ONE_WAY_MS = 50;
const FRAME_MS = 1000 / 60;
const KBPS_GOAL_4 = 8;

/** Predicted play as a game would set it up, except that the bench never falls back to snapshots: it measures predict mode. */
const PREDICT = nodePredictOptions({ fallbackAfterMs: Number.POSITIVE_INFINITY });

const sleep = (ms: number): Promise<void> => new Promise((resolve) => setTimeout(resolve, ms));

interface Rig {
  server: GameServer;
  net: MemoryNetwork;
  clock: RealClock;
  room(scenario: string): Promise<string>;
  close(): Promise<void>;
}

async function rig(): Promise<Rig> {
  const clock = new RealClock();
  const logger = silentLogger();
  const server = await GameServer.create({
    factory: createRoomFactory({ scenarios: registryScenarios(), logger }),
    defaultScenario: 'character-course',
    clock,
    logger,
    metrics: createMetrics({ processMetrics: false }),
    maxRooms: 16,
    resumeGraceMs: 0,
  });
  const net = new MemoryNetwork(clock, { latencyMs: ONE_WAY_MS, jitterMs: 0 });
  net.listen(URL, (peer) => server.accept(memoryPeerConnection(peer)));
  let n = 0;
  return {
    server,
    net,
    clock,
    async room(scenario) {
      const id = `${scenario}-bench-${++n}`;
      await server.rooms.create(id, scenario, {});
      return id;
    },
    close: () => server.close('bench done'),
  };
}

function wander(rng: Prng): InputCommand {
  return { moveX: rng.int(-127, 127), moveZ: rng.int(0, 127), yaw: rng.int(0, 65535), pitch: 0, buttons: rng.next() < 0.1 ? 1 : 0 };
}

async function connected(c: NetClient): Promise<void> {
  await c.whenConnected();
}

/** One room: `predicting` predicting players wandering plus bots up to `players`; numbers after `seconds`. */
async function session(r: Rig, scenario: string, players: number, predicting: number, seconds: number): Promise<{ stats: PredictionStats[]; kbps: number[]; kbpsAt60Hz: number[]; botKbps: number; playedSeconds: number; ticksPerSecond: number }> {
  const room = await r.room(scenario);
  const bots = startBots({ url: URL, count: players - predicting, room, clock: r.clock, transport: r.net.transport, seed: scenario, joinSpacingMs: 20 });
  const clients = Array.from({ length: predicting }, (_, i) => connect(URL, { name: `p${i}`, room, clock: r.clock, transport: r.net.transport, reconnect: false, predict: PREDICT }));
  await Promise.all(clients.map(connected));
  const rngs = clients.map((_, i) => new Prng(`${scenario}-${i}`));
  const steer = setInterval(() => clients.forEach((c, i) => c.setInput(wander(rngs[i]))), 200);
  // Warm-up (checkpoint, joins), then the measured window.
  await sleep(2000);
  const from = clients.map((c) => c.stats().bytesIn);
  const fromTick = clients.map((c) => c.stats().prediction?.confirmedTick ?? 0);
  const startedMs = performance.now();
  await sleep(seconds * 1000);
  const playedSeconds = (performance.now() - startedMs) / 1000;
  clearInterval(steer);
  const bytes = clients.map((c, i) => c.stats().bytesIn - from[i]);
  const ticks = clients.map((c, i) => (c.stats().prediction?.confirmedTick ?? 0) - fromTick[i]);
  const kbps = bytes.map((b) => (b * 8) / 1000 / playedSeconds);
  // Per confirmed tick, at 60 ticks a second: what a client gets from a room that keeps real time, however loaded
  // this machine is (a room that falls behind sends fewer records per second).
  const kbpsAt60Hz = bytes.map((b, i) => (ticks[i] > 0 ? (b / ticks[i]) * 60 * 8 / 1000 : Number.NaN));
  const ticksPerSecond = Math.max(...ticks) / playedSeconds;
  const stats = clients.map((c) => c.stats().prediction!).filter((p) => p !== null);
  bots.stop();
  const report = await bots.done;
  for (const c of clients) c.close();
  await r.server.rooms.get(room)?.close('bench session done');
  return { stats, kbps, kbpsAt60Hz, botKbps: report.kbpsInPerBot, playedSeconds, ticksPerSecond };
}

/** The own character walks under this press: it faces the press's yaw and moves. */
function walking(c: CharacterState | undefined, cmd: InputCommand): boolean {
  return c !== undefined && Math.abs(c.yaw - commandYawRadians(cmd)) < 0.01 && Math.hypot(c.velocity.x, c.velocity.z) > 0.5;
}

/** Key → first 60 Hz frame whose own character moves, for a predicting and a snapshot client side by side. */
async function keyToMotion(r: Rig, presses: number): Promise<{ predict: number[]; snapshot: number[] }> {
  const room = await r.room('character-course');
  const bots = startBots({ url: URL, count: 2, room, clock: r.clock, transport: r.net.transport, seed: 'key', joinSpacingMs: 20 });
  const pred = connect(URL, { name: 'pred', room, clock: r.clock, transport: r.net.transport, reconnect: false, predict: PREDICT });
  const snap = connect(URL, { name: 'snap', room, clock: r.clock, transport: r.net.transport, reconnect: false });
  await Promise.all([connected(pred), connected(snap)]);
  await sleep(2500);
  const out = { predict: [] as number[], snapshot: [] as number[] };
  const idle: InputCommand = { moveX: 0, moveZ: 0, yaw: 0, pitch: 0, buttons: 0 };
  for (let i = 0; i < presses; i++) {
    pred.setInput(idle);
    snap.setInput(idle);
    await sleep(700);
    const walk: InputCommand = { ...idle, moveZ: 127, yaw: 4096 + ((i * 7919) % 57344) };
    // The key goes down somewhere inside a frame.
    await sleep(Math.random() * FRAME_MS);
    const pressedMs = performance.now();
    pred.setInput(walk);
    snap.setInput(walk);
    let predSeen: number | null = null;
    let snapSeen: number | null = null;
    while ((predSeen === null || snapSeen === null) && performance.now() - pressedMs < 2000) {
      await sleep(FRAME_MS);
      const now = performance.now();
      if (predSeen === null && walking(pred.predicted()?.characters.find((c) => c.playerId === pred.playerId), walk)) predSeen = now - pressedMs;
      if (snapSeen === null && walking(snap.sample().view?.characters.find((c) => c.playerId === snap.playerId), walk)) snapSeen = now - pressedMs;
    }
    if (predSeen !== null) out.predict.push(predSeen);
    if (snapSeen !== null) out.snapshot.push(snapSeen);
  }
  bots.stop();
  await bots.done;
  pred.close();
  snap.close();
  await r.server.rooms.get(room)?.close('bench session done');
  return out;
}

async function run(opts: { quick: boolean; log(m: string): void }): Promise<FigureOutput> {
  const r = await rig();
  const notes: string[] = [];
  try {
    const presses = opts.quick ? 8 : 20;
    opts.log(`key → motion: ${presses} presses, predict and snapshot clients side by side, ${2 * ONE_WAY_MS} ms RTT`);
    const key = await keyToMotion(r, presses);
    const kp = key.predict.length > 0 ? summarize(key.predict) : null;
    const ks = key.snapshot.length > 0 ? summarize(key.snapshot) : null;
    if (!kp || !ks) notes.push(`key → motion: the own character was not seen moving within 2 s in ${presses - key.predict.length} (predict) and ${presses - key.snapshot.length} (snapshot) of ${presses} presses`);
    const seconds = opts.quick ? 6 : 10;
    const bandwidth: Record<string, { players: number; kbpsPredict: number; kbpsPredictWall: number; confirmedTicksPerSecond: number; kbpsSnapshotBot: number; rollbackDepthP99: number; resimMsP99: number }> = {};
    let played = 0;
    let desyncs = 0;
    const perScenario: Record<string, { rollbackDepthP50: number; rollbackDepthP99: number; resimMsP50: number; resimMsP99: number; corrections: number; desyncs: number; hashesVerified: number; mode: string }> = {};
    for (const scenario of ['character-course', 'cubes-901']) {
      for (const players of opts.quick ? [4] : [4, 16]) {
        opts.log(`bandwidth: ${scenario}, ${players} players (2 predicting), ${seconds} s`);
        const s = await session(r, scenario, players, 2, seconds);
        played += s.playedSeconds * s.stats.length;
        desyncs += s.stats.reduce((a, p) => a + p.desyncs, 0);
        bandwidth[`${scenario}/${players}`] = {
          players,
          kbpsPredict: round(Math.max(0, ...s.kbpsAt60Hz.filter(Number.isFinite)), 2),
          kbpsPredictWall: round(Math.max(...s.kbps), 2),
          confirmedTicksPerSecond: round(s.ticksPerSecond, 1),
          kbpsSnapshotBot: round(s.botKbps, 2),
          rollbackDepthP99: Math.max(...s.stats.map((p) => p.rollbackDepthP99)),
          resimMsP99: round(Math.max(...s.stats.map((p) => p.resimMsP99)), 3),
        };
      }
    }
    const others = listScenarios()
      .map((d) => d.name)
      .filter((n) => opts.quick ? n === 'shape-rain' : true);
    for (const scenario of others) {
      opts.log(`rollback: ${scenario}, 4 players (1 predicting), ${seconds} s`);
      const s = await session(r, scenario, 4, 1, seconds);
      played += s.playedSeconds * s.stats.length;
      const p = s.stats[0];
      if (!p) {
        notes.push(`${scenario}: the room did not offer predict mode`);
        continue;
      }
      desyncs += p.desyncs;
      perScenario[scenario] = { rollbackDepthP50: p.rollbackDepthP50, rollbackDepthP99: p.rollbackDepthP99, resimMsP50: round(p.resimMsP50, 3), resimMsP99: round(p.resimMsP99, 3), corrections: p.corrections, desyncs: p.desyncs, hashesVerified: p.hashesVerified, mode: p.mode };
    }
    const kbps4 = Math.max(...Object.values(bandwidth).filter((b) => b.players === 4).map((b) => b.kbpsPredict));
    const sixteen = Object.values(bandwidth).filter((b) => b.players === 16);
    const kbps16 = sixteen.length > 0 ? Math.max(...sixteen.map((b) => b.kbpsPredict)) : null;
    const depthP99 = Math.max(...Object.values(perScenario).map((p) => p.rollbackDepthP99));
    const resimP99 = Math.max(...Object.values(perScenario).map((p) => p.resimMsP99));
    const desyncsPerHour = played > 0 ? (desyncs * 3600) / played : null;
    notes.push(
      `All in one process on the real clock: the server (GameServer), client-library players and bots over a MemoryNetwork link with ${ONE_WAY_MS} ms each way. Key → motion: the key goes down at a random point inside a frame; the time is to the first 60 Hz frame whose own character moves (predicted() in predict mode, sample() in snapshot mode).`,
      'Bandwidth: bytes received by a predicting client (records, hashes, pongs; no snapshots, no events) per confirmed tick over the measured window, at 60 ticks a second (what a room that keeps real time sends; detail.bandwidth also has the wall-clock kbps and the confirmed ticks per second this machine managed); the snapshot-mode bots in the same room beside it (wall clock).',
      `Rollback depth and re-sim ms are per frame (the input loop, twice per tick), p99 over the last 600 frames of each predicting client; the headline is the worst scenario. Desyncs per hour over ${round(played / 60, 1)} predicting-client minutes (${desyncs} desyncs).`,
    );
    if (opts.quick) notes.push('Quick run: 4 players only (no 16-player bandwidth), shape-rain only for the per-scenario rollback figures.');
    return {
      headline: {
        keyToMotionMsPredict: kp ? round(kp.median, 1) : null,
        keyToMotionMsSnapshot: ks ? round(ks.median, 1) : null,
        kbpsPredict4: round(kbps4, 2),
        kbpsPredict16: kbps16 === null ? null : round(kbps16, 2),
        rollbackDepthP99: depthP99,
        resimMsP99: round(resimP99, 3),
        desyncsPerHour: desyncsPerHour === null ? null : round(desyncsPerHour, 2),
      },
      detail: { rttMs: 2 * ONE_WAY_MS, keyToMotionMs: { predict: kp, snapshot: ks }, bandwidth, perScenario, predictingMinutes: round(played / 60, 2), desyncs },
      rows: [
        { figure: 'predicted play', measure: `key → own motion on screen, predict mode, ${2 * ONE_WAY_MS} ms RTT (median of ${key.predict.length})`, value: kp?.median ?? null, unit: 'ms', digits: 1, goal: { op: '<=', value: round(FRAME_MS, 1) } },
        { figure: 'predicted play', measure: `key → own motion on screen, snapshot mode (median of ${key.snapshot.length})`, value: ks?.median ?? null, unit: 'ms', digits: 1 },
        { figure: 'predicted play', measure: 'kbps per predicting client, 4 players (worst of cubes-901, character-course)', value: kbps4, unit: 'kbps', digits: 2, goal: { op: '<=', value: KBPS_GOAL_4 } },
        { figure: 'predicted play', measure: 'kbps per predicting client, 16 players', value: kbps16, unit: 'kbps', digits: 2 },
        { figure: 'predicted play', measure: 'rollback depth per frame, p99 (worst scenario)', value: depthP99, unit: 'ticks', digits: 0 },
        { figure: 'predicted play', measure: 're-simulation per frame, p99 (worst scenario)', value: resimP99, unit: 'ms', digits: 2 },
        { figure: 'predicted play', measure: 'desyncs per hour of predicted play', value: desyncsPerHour, unit: '/h', digits: 2, goal: { op: '<=', value: 0 } },
      ],
      charts: [
        {
          title: `Key → own motion on screen at ${2 * ONE_WAY_MS} ms RTT (ms)`,
          unit: 'ms',
          bars: [
            { label: 'predict mode (median)', value: kp?.median ?? null, series: 'ours' },
            { label: 'snapshot mode (median)', value: ks?.median ?? null, series: 'baseline' },
            { label: 'one frame', value: FRAME_MS, series: 'raw' },
          ],
        },
      ],
      notes,
    };
  } finally {
    await r.close();
  }
}

/** The predicted-play figure. */
export const figure: FigureImpl = { run };
