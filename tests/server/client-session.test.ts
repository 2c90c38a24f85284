// Tests for server/client-session.ts: every kind of bad client traffic gets an error or a disconnect with a reason,
// the other players' world is untouched (identical hash sequence), slow readers get snapshots skipped, not queued.
import { pino } from 'pino';
import { afterEach, describe, expect, it } from 'vitest';
import { ByeReason, ClientOpcode, ErrorCode, packValue, PROTOCOL_VERSION } from '../../shared/protocol/index.ts';
import { Button, NEUTRAL_INPUT, type InputCommand } from '../../shared/sim/input.ts';
import { memoryPeerConnection } from '../../server/memory-peer.ts';
import { MemoryNetwork } from '../../sdk/index.ts';
import { startHarness, TestClient, type Harness } from './harness.ts';
import { stripScenario } from './test-scenarios.ts';

let h: Harness | null = null;
afterEach(async () => {
  await h?.close();
  h = null;
});

const walk = (moveX: number, moveZ = 0, buttons = 0): InputCommand => ({ ...NEUTRAL_INPUT, moveX, moveZ, buttons });
const byes = (c: TestClient) => c.ofType('bye');
const errorCodes = (c: TestClient) => c.ofType('error').map((e) => e.code);

/** A scripted two-player session; `extra` runs before each tick to add hostile traffic. Returns the hashes. */
async function scriptedSession(extra?: (h: Harness, tick: number, b: TestClient) => void): Promise<string[]> {
  const harness = await startHarness({ scenarios: [stripScenario], params: { boxes: 8 } });
  h = harness;
  const a = await harness.join('ann');
  const b = await harness.join('bob');
  for (let i = 0; i < 150; i++) {
    const next = harness.room().sim.tick + 2;
    a.input(next, [walk(i % 40 < 20 ? 127 : -60, 40, i % 50 === 0 ? 1 : 0)]);
    b.input(next, [walk(-90, i % 30 < 15 ? 127 : -127)]);
    extra?.(harness, i, b);
    harness.ticks(1);
  }
  const { hashes, records } = harness.history();
  expect(records.length).toBeGreaterThan(150);
  expect(a.closed).toBeNull();
  expect(b.closed).toBeNull();
  expect(b.ofType('error').length).toBe(extra ? 10 : 0);
  await harness.close();
  h = null;
  return hashes;
}

describe('ClientSession', () => {
  it('answers malformed, mistyped, NaN and out-of-place messages with errors and keeps the connection', async () => {
    h = await startHarness({ scenarios: [stripScenario] });
    const c = await h.join('ann');
    c.end.send(Uint8Array.of(0xc1, 0xff, 0x00)); // not msgpack
    c.end.sendText('{"hello":1}');
    c.end.send(packValue([99, 1, 2]));
    c.end.send(packValue([2, 10, [[Number.NaN, 0, 0, 0, 0]]]));
    c.end.send(packValue([2, 10, [[0, 0, 0, 0, 0]], 'extra']));
    c.hello('again');
    c.end.send(new Uint8Array(5000));
    h.ticks(2);
    expect(errorCodes(c)).toEqual([ErrorCode.Malformed, ErrorCode.Malformed, ErrorCode.BadMessage, ErrorCode.BadInput, ErrorCode.BadMessage, ErrorCode.UnexpectedMessage, ErrorCode.Oversize]);
    expect(c.closed).toBeNull();
    expect(h.room().clientCount).toBe(1);
    const metrics = await h.server.metrics.registry.getSingleMetricAsString('taos_bad_messages_total');
    expect(metrics).toContain(`reason="${ErrorCode.BadInput}"} 1`);
    // Out-of-range numbers are clamped, not refused: accepted, and counted.
    const tick = h.room().sim.tick + 2;
    c.end.send(packValue([2, tick, [[500, -500, 70000, 99999, 1]]]));
    h.ticks(4);
    expect(errorCodes(c)).toHaveLength(7);
    expect(await h.server.metrics.registry.getSingleMetricAsString('taos_inputs_clamped_total')).toMatch(/ 1$/);
    const applied = h.history().records.find((r) => r.tick === tick)?.commands.find((cmd) => cmd.playerId === c.playerId)?.input;
    expect(applied).toEqual({ moveX: 127, moveZ: -127, yaw: 70000 - 65536, pitch: 16384, buttons: 1 });
  });

  it('gives clients that share or differ in baseline every spawned body descriptor and the same events', async () => {
    h = await startHarness({ scenarios: [stripScenario], snapshotRateHz: 60 });
    const shooter = await h.join('ann');
    const watcher = await h.join('bob');
    const lagger = await h.join('cat');
    lagger.autoAck = false; // never acks: full snapshots, a baseline of its own
    h.ticks(2);
    const from = h.room().sim.tick; // every client is in the world from here on
    const since = (c: TestClient) => c.events.filter((e) => e.tick >= from);
    for (let i = 0; i < 90; i++) {
      shooter.input(h.room().sim.tick + 2, [walk(0, 0, i % 10 === 0 ? Button.Fire : 0)]);
      h.ticks(1);
    }
    const spawned = since(shooter).filter((e) => e.type === 'bodySpawned').map((e) => (e as { bodyId: number }).bodyId);
    expect(spawned.length).toBeGreaterThan(3);
    for (const c of [shooter, watcher, lagger]) {
      expect(since(c)).toEqual(since(shooter));
      const described = new Set([...c.welcome!.dynamicBodies, ...c.ofType('snapshot').flatMap((m) => m.descriptors)].map((d) => d.id));
      const seen = new Set(c.frames.flatMap((f) => Array.from(f.bodyIds)));
      for (const id of spawned) if (seen.has(id)) expect(described.has(id)).toBe(true);
      expect(spawned.some((id) => seen.has(id))).toBe(true);
    }
  });

  it("answers a ping with the room's tick, the player's missed inputs and the room's pace", async () => {
    h = await startHarness({ scenarios: [stripScenario] });
    const c = await h.join('ann');
    for (let i = 0; i < 150; i++) {
      h.ticks(1);
      await h.settle(() => true, 1);
    }
    c.send({ type: 'ping', clientTimeMs: 5 });
    await h.settle(() => c.ofType('pong').length > 0);
    const pong = c.ofType('pong')[0];
    expect(pong).toMatchObject({ clientTimeMs: 5, serverTick: h.room().sim.tick, roomTicksPerSecond: 60, roomSlow: false });
    expect(pong.missedInputTicks).toBeGreaterThan(0);
  });

  it('refuses input and acks before the welcome', async () => {
    h = await startHarness({ scenarios: [stripScenario] });
    const c = h.connect();
    c.input(5, [walk(1)]);
    c.send({ type: 'ack', tick: 3 });
    h.ticks(1);
    expect(errorCodes(c)).toEqual([ErrorCode.UnexpectedMessage, ErrorCode.UnexpectedMessage]);
  });

  it('disconnects a client that keeps sending bad messages, with the reason', async () => {
    h = await startHarness({ scenarios: [stripScenario] });
    const c = h.connect();
    for (let i = 0; i < 30; i++) c.end.send(Uint8Array.of(0xc1));
    h.ticks(2);
    expect(byes(c)).toEqual([expect.objectContaining({ reason: ByeReason.TooManyErrors })]);
    expect(c.closed?.code).toBe(1008);
    expect(h.server.sessionCount()).toBe(0);
  });

  it('disconnects a flood of valid messages beyond the per-client rate', async () => {
    h = await startHarness({ scenarios: [stripScenario] });
    const c = await h.join('fl');
    for (let i = 0; i < 1500; i++) c.send({ type: 'ping', clientTimeMs: i }); // past the 1200-message burst
    h.ticks(2);
    expect(byes(c)).toEqual([expect.objectContaining({ reason: ByeReason.Flood })]);
    expect(h.room().clientCount).toBe(0);
  });

  it('disconnects an input flood even when the total message rate is allowed', async () => {
    h = await startHarness({ scenarios: [stripScenario], limits: { inputs: { perSecond: 60, burst: 20 } } });
    const c = await h.join('fl');
    for (let i = 0; i < 40; i++) c.input(h.room().sim.tick + 2, [walk(1)]);
    h.ticks(2);
    expect(byes(c)[0]?.reason).toBe(ByeReason.Flood);
    expect(byes(c)[0]?.message).toMatch(/input/);
  });

  it('closes oversize frames at the transport like ws does and counts them', async () => {
    h = await startHarness({ scenarios: [stripScenario], maxPayloadBytes: 1024 });
    const c = await h.join('big');
    c.end.send(new Uint8Array(4096));
    h.ticks(2);
    expect(c.closed?.code).toBe(1009);
    expect(h.room().clientCount).toBe(0);
    expect(await h.server.metrics.registry.getSingleMetricAsString('taos_disconnects_total')).toContain('reason="oversize"} 1');
  });

  it('ends a connection that never says hello, and refuses a protocol version it does not speak', async () => {
    h = await startHarness({ scenarios: [stripScenario], limits: { helloTimeoutMs: 500 } });
    const silent = h.connect();
    const old = h.connect();
    old.send({ type: 'hello', version: 999, name: 'old', room: null });
    const v1 = h.connect();
    v1.end.send(packValue([ClientOpcode.Hello, 1, 'v1', null])); // a version-1 client's hello, byte for byte
    h.ticks(40);
    expect(byes(silent)[0]?.reason).toBe(ByeReason.Timeout);
    expect(byes(old)[0]?.reason).toBe(ByeReason.VersionMismatch);
    expect(errorCodes(v1)).toEqual([ErrorCode.VersionMismatch]);
    expect(byes(v1)[0]).toMatchObject({ reason: ByeReason.VersionMismatch, message: expect.stringContaining(`speaks protocol ${PROTOCOL_VERSION} and the client sent protocol 1`) });
    expect(v1.closed?.code).toBe(1008);
  });

  it('tells its connection about the hello and about kicks for misbehaviour, not about other endings', async () => {
    h = await startHarness({ scenarios: [stripScenario], limits: { helloTimeoutMs: 500 } });
    const conduct = new Map<string, string[]>();
    // Client ends whose server side records what the session reports to its transport (the ws gateway's policy).
    const watched = (name: string): TestClient => {
      const net = new MemoryNetwork(h!.clock);
      const seen: string[] = [];
      conduct.set(name, seen);
      net.listen('mem://watched', (peer) => h!.server.accept(Object.assign(memoryPeerConnection(peer), { helloed: () => seen.push('hello'), kicked: (reason: string) => seen.push(`kicked: ${reason}`) })));
      return new TestClient(net, 'mem://watched', name);
    };
    const polite = watched('polite');
    polite.hello('polite');
    const silent = watched('silent');
    const garbage = watched('garbage');
    for (let i = 0; i < 12; i++) garbage.end.send(Uint8Array.of(0xc1));
    const lost = watched('lost');
    lost.hello('lost', 'nowhere');
    const flooder = watched('flooder');
    flooder.hello('flooder');
    await h.settle(() => polite.welcome !== null && flooder.welcome !== null && lost.closed !== null);
    for (let i = 0; i < 1300; i++) flooder.send({ type: 'ping', clientTimeMs: i });
    h.ticks(40);
    expect(byes(silent)[0]?.reason).toBe(ByeReason.Timeout);
    expect(Object.fromEntries(conduct)).toEqual({
      polite: ['hello'],
      silent: ['kicked: timeout'],
      garbage: ['kicked: too-many-errors'],
      lost: ['hello'],
      flooder: ['hello', 'kicked: flood'],
    });
  });

  it('refuses an unknown room with a reason', async () => {
    h = await startHarness({ scenarios: [stripScenario] });
    const c = h.connect();
    c.hello('x', 'nowhere');
    await h.settle(() => c.closed !== null);
    expect(errorCodes(c)).toEqual([ErrorCode.RoomNotFound]);
    expect(byes(c)[0]?.reason).toBe(ByeReason.RoomNotFound);
  });

  it('makes an exception while handling a message that client\'s error and bye, logged once, and the room goes on', async () => {
    const lines: Array<{ level: number; msg: string }> = [];
    const logger = pino({ level: 'info' }, { write: (line: string) => void lines.push(JSON.parse(line) as { level: number; msg: string }) });
    h = await startHarness({ scenarios: [stripScenario], logger });
    const a = await h.join('ann');
    const b = await h.join('bob');
    const room = h.room();
    const offer = room.offerInputs.bind(room);
    // A stand-in for a server bug that only this client's messages reach.
    room.offerInputs = (playerId, firstTick, commands, tally) => {
      if (playerId === a.playerId) throw new Error('injected fault');
      offer(playerId, firstTick, commands, tally);
    };
    const tick = room.sim.tick + 2;
    for (let i = 0; i < 3; i++) a.input(tick + i, [walk(127)]); // only the first is read: the session has ended
    b.input(tick, [walk(-127)]);
    h.ticks(3);
    expect(a.ofType('error')).toEqual([{ type: 'error', code: ErrorCode.Internal, message: 'the server failed while handling your message' }]);
    expect(byes(a)).toEqual([{ type: 'bye', reason: ByeReason.Kicked, message: 'internal error handling your message' }]);
    expect(a.closed?.code).toBe(1011);
    expect(lines.filter((l) => l.level >= 50).map((l) => l.msg)).toEqual(['handling a client message failed; disconnecting the client']);
    expect(await h.server.metrics.registry.getSingleMetricAsString('taos_message_errors_total')).toMatch(/ 1$/);
    const framesBefore = b.frames.length;
    h.ticks(10);
    expect(b.closed).toBeNull();
    expect(b.frames.length).toBeGreaterThan(framesBefore);
    expect(room.closed).toBe(false);
    expect(room.clientCount).toBe(1);
  });

  it('keeps the room\'s hash sequence identical when hostile clients join the traffic', async () => {
    const clean = await scriptedSession();
    let bob: TestClient | null = null;
    const hostile = await scriptedSession((harness, i, b) => {
      if (i % 50 === 7) {
        // Player 2 itself sends junk alongside its valid inputs (within its error allowance): NaN/Infinity commands
        // for the same ticks, bad msgpack, an oversize frame. All refused; its valid inputs still apply.
        const target = harness.room().sim.tick + 2;
        b.end.send(packValue([2, target, [[Number.NaN, 0, 0, 0, 0]]]));
        b.end.send(packValue([2, target, [[0, 0, Number.POSITIVE_INFINITY, 0, 0]]]));
        b.end.send(Uint8Array.of(0xc1));
        if (i === 57) b.end.send(new Uint8Array(3000));
      }
      if (i === 0) {
        bob = harness.connect('flooder');
      }
      if (bob && i < 20) for (let k = 0; k < 30; k++) bob.send({ type: 'ping', clientTimeMs: k });
      if (i === 5) {
        const junk = harness.connect('junk');
        for (let k = 0; k < 40; k++) junk.end.send(Uint8Array.of(0x92, 0x02, 0xcb));
      }
      if (i % 10 === 3) {
        // A joined client (player 2's neighbour in a real game) sends NaN and out-of-range inputs: refused.
        const room = harness.room();
        const target = room.sim.tick + 2;
        for (const c of [packValue([2, target, [[Number.NaN, 0, 0, 0, 0]]]), packValue([2, target, [[0, 0, Number.POSITIVE_INFINITY, 0, 0]]])]) {
          harness.connect('nan').end.send(c);
        }
      }
    });
    expect(hostile).toHaveLength(clean.length);
    expect(hostile).toEqual(clean);
  });

  it('skips snapshots to a client that stopped reading, then disconnects it before queueing without bound', async () => {
    h = await startHarness({
      // Up to 182 players join: the strip's character budget is lifted for them.
      scenarios: [{ ...stripScenario, players: { ...stripScenario.players, maxPlayers: 200 } }],
      params: { boxes: 40 },
      snapshotRateHz: 60,
      maxClientsPerRoom: 200,
      // Deltas of this quiet strip are a few bytes (protocol 10): snapshots are skipped a few snapshots deep, and the
      // hard limit is reached by join events alone.
      limits: { snapshotSkipBufferedBytes: 60, maxBufferedBytes: 4000 },
    });
    const slow = await h.join('slow');
    const fine = await h.join('fine');
    h.ticks(10); // both have acked a baseline: deltas flow
    slow.end.setStalled(true);
    h.ticks(30);
    const skipped = await h.server.metrics.registry.getSingleMetricAsString('taos_snapshots_skipped_total');
    expect(Number(/ (\d+)$/.exec(skipped)?.[1])).toBeGreaterThan(10);
    expect(fine.frames.length).toBeGreaterThan(35);
    expect(slow.closed).toBeNull();
    // Events are reliable and still queue; once the backlog passes the hard limit the client is let go.
    for (let i = 0; i < 180 && slow.closed === null; i++) {
      await h.join(`j${i}`);
      h.ticks(1);
    }
    expect(slow.closed?.code).toBe(1013);
    slow.end.setStalled(false);
    h.ticks(2);
    expect(byes(slow).at(-1)?.reason).toBe(ByeReason.Timeout);
    expect(byes(slow).at(-1)?.message).toMatch(/too slow/);
  });
});
