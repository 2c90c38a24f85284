// Tests for server/memory-link.ts: latency on the clock, bufferedAmount while stalled, ws-like oversize closes,
// early messages, and close notices on both ends.
import { describe, expect, it } from 'vitest';
import { createMemoryLink } from '../../server/memory-link.ts';
import { ManualClock } from '../../shared/clock.ts';

describe('memory-link', () => {
  it('delivers both ways after the latency, in order, counting queued bytes', () => {
    const clock = new ManualClock();
    const { server, client } = createMemoryLink({ clock, latencyMs: 30 });
    const atServer: number[] = [];
    const atClient: number[] = [];
    client.send(Uint8Array.of(1)); // before the server attached: kept
    server.attach({ message: (d) => atServer.push(d[0]), close: () => {} });
    client.onMessage((d) => atClient.push(d[0]));
    client.send(Uint8Array.of(2));
    server.send(Uint8Array.of(7, 7, 7));
    expect(server.bufferedAmount()).toBe(3);
    clock.advance(29);
    expect([atServer, atClient]).toEqual([[], []]);
    clock.advance(1);
    expect([atServer, atClient]).toEqual([[1, 2], [7]]);
    expect(server.bufferedAmount()).toBe(0);
  });

  it('piles messages up while the client is stalled and hands them over when it reads again', () => {
    const clock = new ManualClock();
    const { server, client } = createMemoryLink({ clock });
    server.attach({ message: () => {}, close: () => {} });
    const got: number[] = [];
    client.onMessage((d) => got.push(d.length));
    client.setStalled(true);
    for (let i = 1; i <= 5; i++) server.send(new Uint8Array(i * 100));
    clock.advance(10);
    expect(got).toEqual([]);
    expect(server.bufferedAmount()).toBe(1500);
    client.setStalled(false);
    expect(got).toEqual([100, 200, 300, 400, 500]);
    expect(server.bufferedAmount()).toBe(0);
  });

  it('closes with 1009 on an oversize message and tells both ends once', () => {
    const clock = new ManualClock();
    const { server, client } = createMemoryLink({ clock, maxPayloadBytes: 16 });
    const closes: string[] = [];
    server.attach({ message: () => {}, close: (code) => closes.push(`server ${code}`) });
    client.onClose((code) => closes.push(`client ${code}`));
    client.send(new Uint8Array(17));
    client.send(Uint8Array.of(1));
    clock.advance(1);
    expect(closes).toEqual(['server 1009', 'client 1009']);
    expect(server.isOpen()).toBe(false);
  });

  it('delivers a bye sent just before the server closes, then the close', () => {
    const clock = new ManualClock();
    const { server, client } = createMemoryLink({ clock, latencyMs: 5 });
    server.attach({ message: () => {}, close: () => {} });
    const seen: string[] = [];
    client.onMessage(() => seen.push('message'));
    client.onClose((code, reason) => seen.push(`close ${code} ${reason}`));
    server.send(Uint8Array.of(1));
    server.close(1001, 'going');
    server.send(Uint8Array.of(2)); // after close: dropped
    clock.advance(10);
    expect(seen).toEqual(['message', 'close 1001 going']);
  });
});
