// Bandwidth, downstream per client on cubes-901: with the figure's scripted bot (its first second, the join, apart from
// the steady rest), with the big cube pushed through the field non-stop, and with everything at rest; our per-client
// delta codec (acks after a 100 ms round trip, every snapshot decoded bit-exact) beside plain msgpackr of every body's
// float pose and @colyseus/schema delta patches of the same state.
import { getScenario } from '../../scenarios/index.ts';
import { BodyFlag } from '../../shared/physics/index.ts';
import { createSnapshotFormat } from '../../shared/protocol/index.ts';
import { Button, MOVE_STEPS, NEUTRAL_INPUT, YAW_STEPS, type InputCommand } from '../../shared/sim/input.ts';
import type { Simulation } from '../../shared/sim/simulation.ts';
import type { TickInputRecord } from '../../shared/sim/types.ts';
import type { FigureImpl, FigureOutput, ReportRow } from '../lib/figure.ts';
import { botRecords, createSceneSim, CUBES_SCENE } from '../lib/scenes.ts';
import { startServerRig } from '../lib/server-rig.ts';
import { SnapshotStreams, type PhaseCounters } from '../lib/snapshot-streams.ts';
import { round } from '../lib/stats.ts';
import { kbps } from '../lib/wire.ts';
import { TICK_MS, TICK_RATE_HZ } from '../../shared/tick-rate.ts';

const RATES_HZ = [60, 30, 20] as const;
const RTT_MS = 100;
const RTT_TICKS = Math.round(RTT_MS / TICK_MS);
const GOAL_KBPS = 128;
/** Issue 14's goals for the coding work: pushed non-stop and at rest, at 60 Hz. */
const GOAL_PUSHED_KBPS = 32;
const GOAL_AT_REST_KBPS = 4;
const JOIN_TICKS = 60;
/** Where the driver steers the big cube, in turn: rows across the 29 m field, there and back. */
const WAYPOINTS: ReadonlyArray<{ x: number; z: number }> = [
  { x: -12, z: 12 },
  { x: 12, z: 12 },
  { x: 12, z: 6 },
  { x: -12, z: 6 },
  { x: -12, z: 0 },
  { x: 12, z: 0 },
  { x: 12, z: -6 },
  { x: -12, z: -6 },
  { x: -12, z: -12 },
  { x: 12, z: -12 },
];
const WAYPOINT_REACHED_METRES = 2.5;

/** Moving bodies now, and how many of them are awake. */
function movingBodies(sim: Simulation): { moving: number; awake: number } {
  const s = sim.readBodyStates();
  let moving = 0;
  let awake = 0;
  for (let i = 0; i < s.count; i++) {
    if ((s.flags[i] & BodyFlag.Dynamic) === 0) continue;
    moving++;
    if ((s.flags[i] & BodyFlag.Active) !== 0) awake++;
  }
  return { moving, awake };
}

/** Player 1 driving the big cube towards the waypoints in turn (sprinting forward, yaw at the next waypoint). */
export function cubeDriver(sim: Simulation): (tick: number) => TickInputRecord {
  let next = 0;
  const bigId = (): number | undefined => sim.descriptors().find((d) => d.motion === 'dynamic' && d.shape.kind === 'box' && d.shape.halfExtents.x >= 1)?.id;
  return (tick) => {
    const id = bigId();
    const s = sim.readBodyStates();
    const i = id === undefined ? -1 : s.ids.indexOf(id);
    let input: InputCommand = { ...NEUTRAL_INPUT, moveZ: MOVE_STEPS, buttons: Button.Sprint };
    if (i >= 0) {
      const x = s.states[i * 13];
      const z = s.states[i * 13 + 2];
      if (Math.hypot(WAYPOINTS[next].x - x, WAYPOINTS[next].z - z) < WAYPOINT_REACHED_METRES) next = (next + 1) % WAYPOINTS.length;
      // Forward is (−sin yaw, −cos yaw): the yaw that faces the waypoint.
      const yaw = Math.atan2(-(WAYPOINTS[next].x - x), -(WAYPOINTS[next].z - z));
      input = { ...input, yaw: ((Math.round((yaw / (2 * Math.PI)) * YAW_STEPS) % YAW_STEPS) + YAW_STEPS) % YAW_STEPS };
    }
    return { tick, leaves: [], joins: tick === 0 ? [{ playerId: 1, name: 'driver' }] : [], commands: [{ playerId: 1, input }] };
  };
}

function newStreams(sim: Simulation, baselines: boolean): SnapshotStreams {
  const format = createSnapshotFormat(getScenario(CUBES_SCENE.scenario).bounds);
  // The welcome carried the descriptors of every moving body alive at tick 0.
  const knownIds = sim.descriptors().filter((d) => d.motion !== 'static').map((d) => d.id);
  return new SnapshotStreams({ format, ratesHz: RATES_HZ, rttTicks: RTT_TICKS, knownIds, baselines });
}

/** Downstream kbps of a phase: snapshots and events (plus extra bytes, e.g. the welcome) over its duration. */
function downKbps(c: PhaseCounters, extraBytes = 0): number {
  return c.ticks > 0 ? kbps(c.snapshotBytes + c.eventBytes + extraBytes, c.ticks / TICK_RATE_HZ) : NaN;
}

async function botRun(seconds: number, log: (m: string) => void): Promise<{ streams: SnapshotStreams; maxMoving: number }> {
  const sim = await createSceneSim(CUBES_SCENE);
  try {
    const streams = newStreams(sim, true);
    const bots = botRecords(1);
    let maxMoving = 0;
    log(`${CUBES_SCENE.label}, the figure's bot: ${seconds} s, snapshots at ${RATES_HZ.join('/')} Hz with both baselines`);
    for (let t = 0; t < seconds * 60; t++) {
      const record = bots.next();
      streams.afterStep(sim, record.tick, sim.step(record), t < JOIN_TICKS ? 'join' : 'steady');
      maxMoving = Math.max(maxMoving, movingBodies(sim).moving);
    }
    return { streams, maxMoving };
  } finally {
    sim.destroy();
  }
}

async function pushedThenRest(pushSeconds: number, restSeconds: number, log: (m: string) => void) {
  const sim = await createSceneSim(CUBES_SCENE);
  try {
    const streams = newStreams(sim, false);
    const drive = cubeDriver(sim);
    const warmTicks = 2 * 60; // the join, and the cube reaching the field
    const awakePushed: number[] = [];
    log(`${CUBES_SCENE.label}, the big cube pushed through the field: ${pushSeconds} s after ${warmTicks / 60} s`);
    for (let t = 0; t < warmTicks + pushSeconds * 60; t++) {
      const record = drive(sim.tick);
      streams.afterStep(sim, record.tick, sim.step(record), t < warmTicks ? 'pushJoin' : 'pushed');
      if (t >= warmTicks) awakePushed.push(movingBodies(sim).awake);
    }
    // Hands off: the driver stands still and everything settles (bounded), then the at-rest window.
    const settleLimitTicks = 30 * 60;
    let settleTicks = 0;
    const idle = (tick: number): TickInputRecord => ({ tick, leaves: [], joins: [], commands: [{ playerId: 1, input: { ...NEUTRAL_INPUT } }] });
    while (settleTicks < settleLimitTicks && movingBodies(sim).awake > 0) {
      const record = idle(sim.tick);
      streams.afterStep(sim, record.tick, sim.step(record), 'settling');
      settleTicks++;
    }
    const awakeAtRestStart = movingBodies(sim).awake;
    log(`at rest after ${(settleTicks / TICK_RATE_HZ).toFixed(1)} s (${awakeAtRestStart} bodies awake): ${restSeconds} s`);
    for (let t = 0; t < restSeconds * 60; t++) {
      const record = idle(sim.tick);
      streams.afterStep(sim, record.tick, sim.step(record), 'atRest');
    }
    const sorted = [...awakePushed].sort((a, b) => a - b);
    return { streams, settleSeconds: settleTicks / 60, awakeAtRestStart, awakePushedMedian: sorted[sorted.length >> 1], awakePushedMax: sorted[sorted.length - 1] };
  } finally {
    sim.destroy();
  }
}

/** The size on the wire of the welcome the real server sends a client joining cubes-901. */
async function welcomeBytes(): Promise<number> {
  const rig = await startServerRig({ scenario: CUBES_SCENE.scenario, params: CUBES_SCENE.params, startBytes: null, clients: 1, snapshotRateHz: 60, oneWayTicks: 3, hashEveryTicks: 600 });
  try {
    return rig.welcomeBytes();
  } finally {
    await rig.close();
  }
}

async function run(opts: { quick: boolean; log(m: string): void }): Promise<FigureOutput> {
  const seconds = opts.quick ? 20 : 60;
  const pushSeconds = opts.quick ? 10 : 30;
  const restSeconds = opts.quick ? 5 : 10;
  const welcome = await welcomeBytes();
  const a = await botRun(seconds, opts.log);
  const b = await pushedThenRest(pushSeconds, restSeconds, opts.log);
  const whole = (hz: number): PhaseCounters => a.streams.phases(hz, ['join', 'steady']);
  const k = (bytes: number, s: number): number => round(kbps(bytes, s), 1);
  const join60 = a.streams.phase(60, 'join');
  const steady60 = a.streams.phase(60, 'steady');
  const pushed60 = b.streams.phase(60, 'pushed');
  const rest60 = b.streams.phase(60, 'atRest');
  const byPhase = (hz: number) => ({
    rateHz: hz,
    joinKbps: round(downKbps(a.streams.phase(hz, 'join'), welcome), 1),
    joinWithoutWelcomeKbps: round(downKbps(a.streams.phase(hz, 'join')), 1),
    steadyKbps: round(downKbps(a.streams.phase(hz, 'steady')), 1),
    pushedKbps: round(downKbps(b.streams.phase(hz, 'pushed')), 1),
    atRestKbps: round(downKbps(b.streams.phase(hz, 'atRest')), 1),
    atRestBytesPerSnapshot: round(b.streams.phase(hz, 'atRest').snapshotBytes / Math.max(1, b.streams.phase(hz, 'atRest').snapshots), 1),
    pushedBytesPerSnapshot: round(b.streams.phase(hz, 'pushed').snapshotBytes / Math.max(1, b.streams.phase(hz, 'pushed').snapshots), 1),
  });
  const perSnapshot = (c: PhaseCounters, us: number): number => round(us / Math.max(1, c.snapshots), 1);
  const decodeUs = { steady: perSnapshot(steady60, steady60.decodeUs), pushed: perSnapshot(pushed60, pushed60.decodeUs) };
  const encodeUs = { steady: perSnapshot(steady60, steady60.encodeUs), pushed: perSnapshot(pushed60, pushed60.encodeUs) };
  const rates = RATES_HZ.map((hz) => {
    const w = whole(hz);
    return { rateHz: hz, oursKbps: k(w.snapshotBytes, seconds), oursMeanSnapshotBytes: round(w.snapshotBytes / w.snapshots, 1), fullSnapshots: w.fullSnapshots, snapshots: w.snapshots, naiveKbps: k(w.naiveBytes, seconds), colyseusKbps: k(w.colyseusBytes, seconds), colyseusPatches: w.colyseusPatches, oursTotalWithEventsKbps: k(w.snapshotBytes + w.eventBytes, seconds) };
  });
  const r60 = rates[0];
  const r20 = rates[2];
  const down = { join: downKbps(join60, welcome), steady: downKbps(steady60), pushed: downKbps(pushed60), atRest: downKbps(rest60) };
  const rows: ReportRow[] = [
    { figure: 'bandwidth', measure: `downstream, join: first second incl. the ${welcome} B welcome (${CUBES_SCENE.label}, 60 Hz)`, value: down.join, unit: 'kbps', digits: 1 },
    { figure: 'bandwidth', measure: `downstream, steady: the figure's bot after its first second (${seconds - 1} s, 60 Hz)`, value: down.steady, unit: 'kbps', digits: 1 },
    { figure: 'bandwidth', measure: `downstream, big cube pushed through the field non-stop (${pushSeconds} s, 60 Hz, median ${b.awakePushedMedian} bodies awake)`, value: down.pushed, unit: 'kbps', digits: 1, goal: { op: '<=', value: GOAL_PUSHED_KBPS } },
    { figure: 'bandwidth', measure: `downstream, at rest (${restSeconds} s, 60 Hz, ${byPhase(60).atRestBytesPerSnapshot} B per snapshot)`, value: down.atRest, unit: 'kbps', digits: 1, goal: { op: '<=', value: GOAL_AT_REST_KBPS } },
    { figure: 'bandwidth', measure: `client decode per snapshot, pushed (Node, ${CUBES_SCENE.label}, 60 Hz; steady ${decodeUs.steady} µs)`, value: decodeUs.pushed, unit: 'µs', digits: 1 },
    { figure: 'bandwidth', measure: `server encode per client snapshot, pushed (unshared: one client; steady ${encodeUs.steady} µs)`, value: encodeUs.pushed, unit: 'µs', digits: 1 },
    { figure: 'bandwidth', measure: `downstream snapshots, whole bot run incl. join (${seconds} s, 60 Hz)`, value: r60.oursKbps, unit: 'kbps', digits: 1, goal: { op: '<=', value: GOAL_KBPS } },
    { figure: 'bandwidth', measure: 'downstream snapshots, whole bot run, 20 Hz', value: r20.oursKbps, unit: 'kbps', digits: 1 },
    { figure: 'bandwidth', measure: 'plain msgpackr of every body, whole bot run, 60 Hz', value: r60.naiveKbps, unit: 'kbps', digits: 0 },
    { figure: 'bandwidth', measure: '@colyseus/schema deltas, whole bot run, 60 Hz', value: r60.colyseusKbps, unit: 'kbps', digits: 1 },
    { figure: 'bandwidth', measure: '@colyseus/schema deltas, whole bot run, 20 Hz', value: r20.colyseusKbps, unit: 'kbps', digits: 1 },
    { figure: 'bandwidth', measure: 'events (reliable, every client, any rate), whole bot run', value: k(whole(60).eventBytes, seconds), unit: 'kbps', digits: 1 },
  ];
  const r1 = (v: number): number | null => (Number.isFinite(v) ? round(v, 1) : null);
  return {
    headline: {
      kbpsJoin60Hz: r1(down.join),
      kbpsSteady60Hz: r1(down.steady),
      kbpsPushed60Hz: r1(down.pushed),
      kbpsAtRest60Hz: r1(down.atRest),
      kbpsPerClient60Hz: r60.oursKbps,
      kbpsPerClient20Hz: r20.oursKbps,
      naiveKbps60Hz: r60.naiveKbps,
      colyseusKbps60Hz: r60.colyseusKbps,
      snapshotDecodeUs60Hz: decodeUs.pushed,
      snapshotEncodeUs60Hz: encodeUs.pushed,
    },
    detail: {
      scene: CUBES_SCENE,
      direction: 'downstream (server → one client)',
      seconds,
      pushSeconds,
      restSeconds,
      rttMs: RTT_MS,
      welcomeBytes: welcome,
      movingBodiesMax: a.maxMoving,
      awakeWhilePushed: { median: b.awakePushedMedian, max: b.awakePushedMax },
      settleSecondsBeforeRest: round(b.settleSeconds, 2),
      awakeAtRestStart: b.awakeAtRestStart,
      eventsKbps: k(whole(60).eventBytes, seconds),
      phases: RATES_HZ.map(byPhase),
      decodeUsPerSnapshot: decodeUs,
      encodeUsPerSnapshot: encodeUs,
      rates,
    },
    rows,
    charts: [
      {
        title: `Downstream per client, ${CUBES_SCENE.label} at 60 Hz (kbps incl. WebSocket framing)`,
        unit: 'kbps (log)',
        log: true,
        bars: [
          { label: 'join (first second, welcome incl.)', value: r1(down.join), series: 'ours' },
          { label: 'steady (the figure’s bot)', value: r1(down.steady), series: 'ours' },
          { label: 'big cube pushed non-stop', value: r1(down.pushed), series: 'ours' },
          { label: 'at rest', value: r1(down.atRest), series: 'ours' },
          { label: '@colyseus/schema, whole bot run', value: r60.colyseusKbps, series: 'baseline' },
          { label: 'plain msgpackr, whole bot run', value: r60.naiveKbps, series: 'baseline' },
        ],
      },
    ],
    notes: [
      `Downstream (server → one client) on ${CUBES_SCENE.label}, seed 1, 60 Hz snapshots unless said otherwise, acks ${RTT_MS} ms (${RTT_TICKS} ticks) after each snapshot; every snapshot was decoded and matched the server's frame bit for bit. Sizes include the WebSocket header.`,
      `Join, steady, pushed and at rest count everything the client receives: snapshot messages (the opcode byte and range-coded delta, or a msgpack envelope when descriptors of spawned bodies ride along) and events (joins, spawns, removals, sensors); join adds the ${welcome} B welcome the real server sends (scene and ${CUBES_SCENE.label}'s body descriptors). Join and steady: the figure's bot (player 1 rolls the big cube, walks, jumps, fires), split at its first second. Pushed: a driver steers the big cube along rows across the field for ${pushSeconds} s (after 2 s to join and reach it), at most ${b.awakePushedMax} bodies awake. At rest: the driver stands still until no body is awake (${round(b.settleSeconds, 1)} s here), then ${restSeconds} s.`,
      `Whole-run keys (kbpsPerClient60Hz/20Hz, naiveKbps60Hz, colyseusKbps60Hz) are snapshot messages only over the bot's ${seconds} s, join included, the codec comparison: plain msgpackr is [opcode, tick, [[id, x, y, z, qx, qy, qz, qw]…], characters] with float32 numbers every snapshot; Colyseus a Schema with a MapSchema of bodies (float32 fields, the same quantized values), one patch per snapshot tick over its reliable stream (empty patches not sent), plus its 1-byte protocol code.`,
    ],
  };
}

/** The bandwidth figure. */
export const figure: FigureImpl = { run };
