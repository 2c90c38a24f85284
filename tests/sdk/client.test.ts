// Tests of the network client against a fake server over the in-memory network on a manual clock: handshake, clock
// sync, inputs that arrive ahead of their tick, snapshots decoded exactly and acked into deltas, interpolation,
// events, errors, reconnects with backoff, and the endings that must not reconnect.
import { describe, expect, it } from 'vitest';
import { connect, type NetClient, type NetClientOptions } from '../../sdk/client.ts';
import { MemoryNetwork } from '../../sdk/memory-transport.ts';
import { ManualClock } from '../../shared/clock.ts';
import { ByeReason, ErrorCode, PROTOCOL_VERSION } from '../../shared/protocol/opcodes.ts';
import type { WelcomeMessage } from '../../shared/protocol/server-messages.ts';
import { framesEqual } from '../../shared/protocol/snapshot-frame.ts';
import { NEUTRAL_INPUT } from '../../shared/sim/input.ts';
import type { SimEvent } from '../../shared/sim/types.ts';
import { FakeServer, type FakeServerOptions } from './fake-server.ts';

const URL = 'mem://game';

function world(opts: { latencyMs?: number; jitterMs?: number; server?: FakeServerOptions } = {}) {
  const clock = new ManualClock(1000);
  let seed = 7;
  const net = new MemoryNetwork(clock, {
    latencyMs: opts.latencyMs ?? 40,
    jitterMs: opts.jitterMs ?? 0,
    random: () => {
      seed = (seed * 16807) % 2147483647;
      return seed / 2147483647;
    },
  });
  const server = new FakeServer(clock, net, URL, opts.server);
  server.start();
  const open = (o: Partial<NetClientOptions> = {}): NetClient => connect(URL, { name: 'Ada', room: 'r1', transport: net.transport, clock, random: () => 0.5, ...o });
  return { clock, net, server, open };
}

describe('client', () => {
  it('says hello with its name and room and is welcomed with the scenario and geometry', async () => {
    const w = world();
    const client = w.open();
    const states: string[] = [];
    client.on('state', (s) => states.push(s));
    const welcomed = client.whenConnected();
    w.clock.advance(200);
    const welcome = await welcomed;
    expect(w.server.sessions[0]).toMatchObject({ name: 'Ada', room: 'r1' });
    expect(welcome.playerId).toBe(1);
    expect(client.state).toBe('connected');
    expect(states).toEqual(['connected']);
    expect(client.descriptor(0)?.motion).toBe('static');
    expect(client.dynamicDescriptors().size).toBe(3);
    client.close();
  });

  it('estimates the server tick within a tick over a jittery link', () => {
    const w = world({ latencyMs: 40, jitterMs: 15 });
    const client = w.open();
    w.clock.advance(4000);
    const stats = client.stats();
    expect(Math.abs(client.serverTick()! - w.server.exactTick())).toBeLessThan(1);
    expect(stats.rttMs).toBeGreaterThan(80);
    expect(stats.rttMs).toBeLessThan(110);
    expect(stats.jitterMs).toBeGreaterThan(0);
    client.close();
  });

  it('gets every input to the server before its tick, with repeats, once the lead has settled', () => {
    const w = world({ latencyMs: 50, jitterMs: 20 });
    const client = w.open();
    w.clock.advance(1500);
    const session = w.server.session(client.playerId!);
    const missedBefore = session.missed;
    const startTick = w.server.tick;
    // Changing input every 100 ms: the server must apply exactly what was set, at the ticks the client chose.
    for (let i = 0; i < 40; i++) {
      client.setInput({ ...NEUTRAL_INPUT, moveX: (i % 5) * 20, buttons: i % 2 });
      w.clock.advance(100);
    }
    expect(session.missed - missedBefore).toBe(0);
    expect(client.stats().leadTicks).toBeGreaterThanOrEqual(1);
    // Every tick since had the client's own command in time (none repeated by the server)…
    for (let t = startTick; t < w.server.tick; t++) expect(session.onTime.has(t)).toBe(true);
    // …and the 40 settings show up in order as runs of about 100 ms (6 ticks) each.
    const runs: Array<{ key: string; length: number }> = [];
    for (let t = startTick; t < w.server.tick; t++) {
      const c = session.applied.get(t)!;
      const key = `${c.moveX}/${c.buttons}`;
      if (runs.length > 0 && runs[runs.length - 1].key === key) runs[runs.length - 1].length++;
      else runs.push({ key, length: 1 });
    }
    expect(runs.length).toBeGreaterThanOrEqual(39);
    expect(runs.length).toBeLessThanOrEqual(41);
    for (const r of runs.slice(1, -1)) {
      expect(r.length).toBeGreaterThanOrEqual(5);
      expect(r.length).toBeLessThanOrEqual(7);
    }
    expect(session.received.filter((m) => m === 'input').length).toBeGreaterThan(200);
    client.close();
  });

  it('raises its lead when the server reports late inputs', () => {
    const w = world();
    const client = w.open({ pingIntervalMs: 200 });
    w.clock.advance(1500);
    const before = client.stats().leadTicks!;
    w.server.extraMissed += 4;
    w.clock.advance(400);
    expect(client.stats().leadTicks).toBeCloseTo(before + 0.25, 6); // one report of misses: a quarter tick more
    client.close();
  });

  it('decodes every snapshot to the server frame, acks it on its next input message, and then receives deltas', () => {
    const w = world({ latencyMs: 30, jitterMs: 10 });
    const client = w.open();
    let exact = 0;
    let deltas = 0;
    const ticks: number[] = [];
    client.on('snapshot', (s) => {
      expect(framesEqual(s.frame, w.server.frames.get(s.tick)!)).toBe(true);
      exact++;
      ticks.push(s.tick);
      if (s.baselineTick !== null) deltas++;
    });
    w.clock.advance(3000);
    // Let the last acks land before counting.
    w.server.stop();
    w.clock.advance(100);
    expect(exact).toBeGreaterThan(50);
    expect(deltas).toBeGreaterThan(exact - 5);
    const session = w.server.sessions[0];
    // 20 Hz snapshots and an input message every tick: each ack rides on the next input, none is sent alone.
    expect(session.received.filter((m) => m === 'ack')).toEqual([]);
    expect(session.acked).toEqual(ticks);
    expect(session.encoder.stats.delta).toBeGreaterThan(40);
    expect(client.stats().snapshots).toBe(exact);
    expect(client.stats(w.clock.nowMs() - 100).kbpsIn).toBeGreaterThan(0);
    client.close();
  });

  it('interpolates the world smoothly and shows its own character moving with its input', () => {
    const w = world({ latencyMs: 30, jitterMs: 10 });
    const client = w.open();
    client.setInput({ ...NEUTRAL_INPUT, moveX: 127 });
    w.clock.advance(2000);
    const a = client.sample();
    w.clock.advance(100);
    const b = client.sample();
    expect(a.mode).toBe('interpolating');
    expect(b.renderTick - a.renderTick).toBeGreaterThan(5);
    expect(b.renderTick).toBeLessThan(client.serverTick()!);
    // Body 1 moves 1/60 m per tick along x.
    const x = (f: typeof a): number => f.view!.positions[0];
    expect(x(b) - x(a)).toBeCloseTo((b.renderTick - a.renderTick) / 60, 2);
    const me = (f: typeof a) => f.view!.characters.find((c) => c.playerId === client.playerId)!;
    expect(me(b).position.x).toBeGreaterThan(me(a).position.x + 0.5);
    client.close();
  });

  it('delivers events and server errors as typed events', () => {
    const w = world();
    const client = w.open();
    const events: SimEvent[] = [];
    const errors: string[] = [];
    client.on('events', (e) => events.push(...e));
    client.on('serverError', (e) => errors.push(`${e.code}: ${e.message}`));
    w.clock.advance(300);
    w.server.emit({ type: 'scenario', tick: w.server.tick, name: 'doorOpen', value: 1 });
    w.server.send(w.server.sessions[0], { type: 'error', code: ErrorCode.RateLimited, message: 'slow down' });
    w.clock.advance(200);
    expect(events.map((e) => e.type)).toEqual(['playerJoined', 'scenario']);
    expect(errors).toEqual(['rate-limited: slow down']);
    expect(client.state).toBe('connected');
    client.close();
  });

  it('reconnects with backoff after the link drops and takes its player back with the resume token', async () => {
    const w = world();
    const client = w.open();
    w.clock.advance(500);
    const first = client.playerId;
    const attempts: Array<{ attempt: number; delayMs: number }> = [];
    client.on('reconnecting', (r) => attempts.push({ attempt: r.attempt, delayMs: r.delayMs }));
    const firstToken = client.resumeToken;
    expect(firstToken).toMatch(/^fakeResume/);
    const rewelcomed = new Promise<WelcomeMessage>((resolve) => client.on('welcome', resolve));
    w.net.dropAll();
    w.clock.advance(1);
    expect(client.state).toBe('reconnecting');
    expect(attempts).toEqual([{ attempt: 1, delayMs: 250 }]);
    w.clock.advance(500);
    const second = await rewelcomed;
    expect(w.server.sessions.at(-1)!.hello?.resumeToken).toBe(firstToken);
    expect(second).toMatchObject({ playerId: first, resumed: true });
    expect(client.resumeToken).not.toBe(firstToken);
    expect(client.state).toBe('connected');
    expect(client.stats().reconnects).toBe(1);
    expect(w.server.sessions.at(-1)!.room).toBe('r1');
    w.clock.advance(1000);
    expect(client.sample().view).not.toBeNull();
    client.close();
  });

  it('backs off exponentially while the server is down and gives up after the last attempt', () => {
    const w = world();
    const client = w.open({ reconnect: { maxAttempts: 3, baseDelayMs: 100 } });
    w.clock.advance(500);
    const delays: number[] = [];
    let closed = '';
    client.on('reconnecting', (r) => delays.push(r.delayMs));
    client.on('closed', (c) => (closed = `${c.reason}: ${c.detail}`));
    w.net.unlisten(URL);
    w.net.dropAll();
    w.clock.advance(5000);
    expect(delays).toEqual([100, 200, 400]);
    expect(client.state).toBe('closed');
    expect(closed).toMatch(/^unreachable: gave up after 3 attempts/);
  });

  it('tells a dropped link from a server that went away: a retry that finds nothing listening', () => {
    const w = world();
    const client = w.open({ reconnect: { baseDelayMs: 100 } });
    w.clock.advance(500);
    const seen: boolean[] = [];
    client.on('reconnecting', (r) => seen.push(r.serverRestarting));
    w.net.dropAll(); // a plain drop: the server is still there
    w.clock.advance(500);
    expect(client.state).toBe('connected');
    w.net.unlisten(URL);
    w.net.dropAll(); // the server process is gone: the next attempt finds nothing listening
    w.clock.advance(350);
    const restarted = new FakeServer(w.clock, w.net, URL); // a new process on the same address
    restarted.start();
    w.clock.advance(1000);
    expect(client.state).toBe('connected');
    // drop; drop (the link had worked); two attempts that found nothing listening
    expect(seen).toEqual([false, false, true, true]);
    w.net.dropAll(); // back to a plain drop: the welcome cleared the restart
    w.clock.advance(1);
    expect(seen.at(-1)).toBe(false);
    client.close();
  });

  it('stays closed after a kick and reports the reason', async () => {
    const w = world();
    const client = w.open();
    w.clock.advance(500);
    const byes: string[] = [];
    client.on('bye', (b) => byes.push(b.reason));
    w.server.kick(w.server.sessions[0], ByeReason.Kicked, 'kicked by an admin');
    w.clock.advance(2000);
    expect(byes).toEqual(['kicked']);
    expect(client.state).toBe('closed');
    expect(client.closed).toEqual({ reason: 'kicked', detail: 'kicked: kicked by an admin' });
    expect(w.net.connectionCount).toBe(1);
    await expect(client.whenConnected()).rejects.toThrow(/kicked/);
  });

  it('ends with the server-shutdown reason after a shutdown bye and does not reconnect', () => {
    const w = world();
    const client = w.open();
    w.clock.advance(500);
    const reconnects: number[] = [];
    client.on('reconnecting', (r) => reconnects.push(r.attempt));
    w.server.kick(w.server.sessions[0], ByeReason.ServerShutdown, 'restarting');
    w.clock.advance(5000);
    expect(client.state).toBe('closed');
    expect(client.closed).toEqual({ reason: 'server-shutdown', detail: 'server-shutdown: restarting' });
    expect(reconnects).toEqual([]);
    expect(w.net.connectionCount).toBe(1);
  });

  it('reconnects after a timeout bye', () => {
    const w = world();
    const client = w.open();
    w.clock.advance(500);
    w.server.kick(w.server.sessions[0], ByeReason.Timeout, 'no ping for 10 s');
    w.clock.advance(1000);
    expect(client.state).toBe('connected');
    expect(w.net.connectionCount).toBe(2);
    client.close();
  });

  it('gives up at once when the room is full', async () => {
    const w = world({ server: { refuseWith: { code: ErrorCode.RoomFull, byeReason: ByeReason.RoomFull } } });
    const client = w.open();
    const connected = client.whenConnected();
    w.clock.advance(5000);
    await expect(connected).rejects.toThrow(/room-full/);
    expect(client.closed?.reason).toBe('room-full');
    expect(w.net.connectionCount).toBe(1);
  });

  it('gives up at once when the server refuses the room, and on a protocol version mismatch', async () => {
    const w = world({ server: { refuseWith: { code: ErrorCode.RoomNotFound, byeReason: ByeReason.RoomNotFound } } });
    const client = w.open();
    const connected = client.whenConnected();
    w.clock.advance(1000);
    await expect(connected).rejects.toThrow(/room-not-found/);
    expect(client.closed?.reason).toBe('room-not-found');
    expect(w.net.connectionCount).toBe(1);

    const v = world({ server: { protocolVersion: 99 } });
    const old = v.open();
    v.clock.advance(1000);
    expect(old.closed).toEqual({ reason: 'version-mismatch', detail: `version-mismatch: the server speaks protocol 99 and this client ${PROTOCOL_VERSION}: use a client built for protocol 99` });
    expect(v.net.connectionCount).toBe(1);
  });

  it('follows a room-moved bye to the hosting server at once, with the same hello, and is welcomed there', async () => {
    const w = world({ server: { moveTo: 'mem://host' } });
    const host = new FakeServer(w.clock, w.net, 'mem://host');
    host.start();
    const client = w.open({ seat: 'seat.token-1' });
    const moves: string[] = [];
    client.on('moved', (m) => moves.push(m.url));
    const welcomed = client.whenConnected();
    w.clock.advance(300);
    expect((await welcomed).playerId).toBe(1);
    expect(moves).toEqual(['mem://host']);
    expect(client.url).toBe('mem://host');
    expect(client.stats().reconnects).toBe(0);
    expect(host.sessions[0].hello).toMatchObject({ name: 'Ada', room: 'r1', seatToken: 'seat.token-1' });
    client.close();
  });

  it('gives up with reason room-moved after three moves in a row, or when the URL is not a WebSocket URL', () => {
    const w = world({ server: { moveTo: 'mem://loop' } });
    const loop = new FakeServer(w.clock, w.net, 'mem://loop', { moveTo: URL });
    loop.start();
    const client = w.open();
    const moves: string[] = [];
    client.on('moved', (m) => moves.push(m.url));
    w.clock.advance(1000);
    expect(moves).toEqual(['mem://loop', URL, 'mem://loop']);
    expect(client.closed).toEqual({ reason: 'room-moved', detail: expect.stringContaining('moved 3 times in a row without a welcome') });

    const v = world({ server: { moveTo: 'http://elsewhere/' } });
    const other = v.open();
    v.clock.advance(1000);
    expect(other.closed).toEqual({ reason: 'room-moved', detail: expect.stringContaining('no usable ws:// or wss:// URL to follow') });
    expect(v.net.connectionCount).toBe(1);
  });

  it('says bye on close, stops sending and never reconnects', async () => {
    const w = world();
    const client = w.open();
    w.clock.advance(500);
    const session = w.server.sessions[0];
    client.close();
    client.close();
    w.clock.advance(2000);
    expect(session.byeReceived).toBe(true);
    expect(client.state).toBe('closed');
    expect(client.closed?.reason).toBe('client-closed');
    expect(w.server.sessions).toHaveLength(0);
    expect(w.net.connectionCount).toBe(1);
    await expect(client.whenConnected()).rejects.toThrow(/client-closed/);
  });

  it('refuses bad names, rooms and inputs with clear errors', () => {
    const w = world();
    expect(() => w.open({ name: '' })).toThrow(/connect: name must not be empty/);
    expect(() => w.open({ room: 'no spaces' })).toThrow(/connect: room must be/);
    const client = w.open();
    expect(() => client.setInput({ ...NEUTRAL_INPUT, yaw: Number.POSITIVE_INFINITY })).toThrow(/setInput: yaw/);
    client.close();
  });
});
