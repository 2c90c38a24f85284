// Tests for server/memory-peer.ts: the client library's NetClient over its MemoryNetwork (latency, jitter) plays
// against the in-process server on the manual clock: joining, moving, seeing each other, server byes, and
// reconnecting after a dropped network with the resume token (taken back, or refused once the window is over).
import { afterEach, describe, expect, it } from 'vitest';
import { connect, type NetClient } from '../../sdk/index.ts';
import { NEUTRAL_INPUT } from '../../shared/sim/input.ts';
import { memoryPeerConnection } from '../../server/memory-peer.ts';
import { MEMORY_URL, startHarness, type Harness } from './harness.ts';
import { stripScenario } from './test-scenarios.ts';

let h: Harness | null = null;
afterEach(async () => {
  await h?.close();
  h = null;
});

/** Feet x (m) of a player in a client's newest decoded snapshot. */
function seenX(viewer: NetClient, playerId: number): number | undefined {
  const view = viewer.sample(h!.clock.nowMs() + 10_000).view; // far ahead: the newest state (held or extrapolated)
  return view?.characters.find((c) => c.playerId === playerId)?.position.x;
}

describe('memory-peer (client library against the server)', () => {
  it('lets two NetClients over a lossy-latency network join, move and see each other', async () => {
    h = await startHarness({ scenarios: [stripScenario] });
    const net = h.network({ latencyMs: 40, jitterMs: 10, random: () => 0.5 });
    const a = connect(MEMORY_URL, { name: 'ann', transport: net.transport, clock: h.clock, reconnect: false });
    const b = connect(MEMORY_URL, { name: 'bob', transport: net.transport, clock: h.clock, reconnect: false });
    await h.settle(() => a.state === 'connected' && b.state === 'connected');
    expect([a.playerId, b.playerId].sort()).toEqual([1, 2]);
    h.ticks(60);
    const bStart = seenX(a, b.playerId!)!;
    const aStart = seenX(b, a.playerId!)!;
    expect(bStart).toBeDefined();
    const missedBefore = h.room().missedInputTicks(a.playerId!);
    a.setInput({ ...NEUTRAL_INPUT, moveX: 127 });
    b.setInput({ ...NEUTRAL_INPUT, moveX: -127 });
    h.ticks(90);
    expect(seenX(b, a.playerId!)! - aStart).toBeGreaterThan(2);
    expect(seenX(a, b.playerId!)! - bStart).toBeLessThan(-2);
    // Once the clock is synced, inputs arrive ahead of their ticks: the server never has to repeat one.
    expect(h.room().missedInputTicks(a.playerId!) - missedBefore).toBe(0);
    expect(a.stats().rttMs).toBeGreaterThan(70);
    a.close();
    b.close();
  });

  it('ends the client with the server\'s reason when the server shuts down', async () => {
    h = await startHarness({ scenarios: [stripScenario] });
    const net = h.network({ latencyMs: 5 });
    const a = connect(MEMORY_URL, { name: 'ann', transport: net.transport, clock: h.clock, reconnect: false });
    await h.settle(() => a.state === 'connected');
    const closing = h.server.close('maintenance');
    await h.settle(() => a.state === 'closed');
    await closing;
    expect(a.closed?.reason).toBe('server-shutdown');
    expect(a.closed?.detail).toMatch(/maintenance/);
    h = null;
  });

  it('takes its player back after the network drops, and carries on as a new player once the grace window is over', async () => {
    h = await startHarness({ scenarios: [stripScenario], resumeGraceMs: 3000 });
    const net = h.network({ latencyMs: 10 });
    const a = connect(MEMORY_URL, { name: 'ann', transport: net.transport, clock: h.clock, reconnect: { baseDelayMs: 200, maxDelayMs: 5000 }, random: () => 0.5 });
    await h.settle(() => a.state === 'connected');
    const first = a.playerId!;
    const welcomes: Array<{ playerId: number; resumed: boolean }> = [];
    const refusals: string[] = [];
    a.on('welcome', (w) => welcomes.push({ playerId: w.playerId, resumed: w.resumed }));
    a.on('serverError', (e) => refusals.push(`${e.code}: ${e.message}`));
    net.dropAll();
    await h.settle(() => welcomes.length === 1);
    expect(welcomes).toEqual([{ playerId: first, resumed: true }]);
    expect(refusals).toEqual([]);

    // Down for longer than the window: the held player leaves, the reconnect's token is refused, a new player joins.
    net.unlisten(MEMORY_URL);
    net.dropAll();
    h.clock.advance(4000);
    net.listen(MEMORY_URL, (peer) => h!.server.accept(memoryPeerConnection(peer))); // the server is reachable again
    await h.settle(() => welcomes.length === 2, 20_000);
    expect(welcomes[1].resumed).toBe(false);
    expect(welcomes[1].playerId).not.toBe(first);
    expect(refusals).toEqual([expect.stringMatching(/^resume-refused: cannot resume: the resume token expired/)]);
    expect(a.state).toBe('connected');
    expect(h.room().hasPlayer(first)).toBe(false);
    a.close();
  });
});
