// Tests of the in-memory network: handshake order, latency, jitter that keeps message order, clean closes that
// deliver what is in flight, abrupt drops that lose it, refused connections, stalled readers, text frames and
// ws-like oversize closes.
import { describe, expect, it } from 'vitest';
import { MemoryNetwork, type MemoryNetworkOptions, type MemoryPeer } from '../../sdk/memory-transport.ts';
import { ManualClock } from '../../shared/clock.ts';

function setup(opts: MemoryNetworkOptions = {}) {
  const clock = new ManualClock(0);
  const net = new MemoryNetwork(clock, opts);
  const peers: MemoryPeer[] = [];
  const serverGot: number[] = [];
  const serverText: string[] = [];
  net.listen('mem://a', (p) => {
    peers.push(p);
    p.onMessage((d, binary) => (binary ? serverGot.push(d[0]) : serverText.push(new TextDecoder().decode(d))));
  });
  const log: string[] = [];
  const got: number[] = [];
  const sizes: number[] = [];
  const t = net.connect('mem://a', {
    open: () => log.push(`open@${clock.nowMs()}`),
    message: (d) => (got.push(d[0]), sizes.push(d.length)),
    close: (code, reason) => log.push(`close ${code} ${reason}@${clock.nowMs()}`),
  });
  return { clock, net, peers, serverGot, serverText, log, got, sizes, t };
}

describe('memory-transport', () => {
  it('opens after one latency and delivers each way after the latency', () => {
    const s = setup({ latencyMs: 30 });
    s.clock.advance(29);
    expect(s.log).toEqual([]);
    s.clock.advance(1);
    expect(s.log).toEqual(['open@30']);
    s.t.send(new Uint8Array([7]));
    s.peers[0].send(new Uint8Array([9]));
    s.clock.advance(29);
    expect([s.serverGot, s.got]).toEqual([[], []]);
    s.clock.advance(1);
    expect([s.serverGot, s.got]).toEqual([[7], [9]]);
  });

  it('keeps order under jitter and counts bytes in flight', () => {
    const s = setup({ latencyMs: 10, jitterMs: 50 });
    s.clock.advance(10);
    for (let i = 0; i < 100; i++) s.peers[0].send(new Uint8Array([i, 0, 0]));
    expect(s.peers[0].bufferedAmount()).toBe(300);
    s.clock.advance(100);
    expect(s.got).toEqual(Array.from({ length: 100 }, (_, i) => i));
    expect(s.peers[0].bufferedAmount()).toBe(0);
  });

  it('delivers messages sent before a clean close, then the close to both ends', () => {
    const s = setup({ latencyMs: 5, jitterMs: 20 });
    let serverClosed = '';
    s.clock.advance(5);
    s.peers[0].onClose((code, reason) => (serverClosed = `${code} ${reason}`));
    s.peers[0].send(new Uint8Array([1]));
    s.peers[0].send(new Uint8Array([2]));
    s.peers[0].close(4000, 'bye now');
    s.peers[0].send(new Uint8Array([3]));
    s.clock.advance(100);
    expect(s.got).toEqual([1, 2]);
    expect(s.log.at(-1)).toMatch(/^close 4000 bye now/);
    expect(serverClosed).toBe('4000 bye now');
  });

  it('loses what is in flight when the network drops every link', () => {
    const s = setup({ latencyMs: 20 });
    s.clock.advance(20);
    s.peers[0].send(new Uint8Array([1]));
    s.net.dropAll();
    s.clock.advance(100);
    expect(s.got).toEqual([]);
    expect(s.log).toEqual(['open@20', 'close 1006 connection lost@20']);
  });

  it('refuses connections to a URL nobody listens on', () => {
    const clock = new ManualClock(0);
    const net = new MemoryNetwork(clock, { latencyMs: 15 });
    const log: string[] = [];
    net.transport('mem://nobody', { open: () => log.push('open'), message: () => undefined, close: (c, r) => log.push(`${c} ${r}`) });
    clock.advance(15);
    expect(log).toEqual(['1006 connection to mem://nobody refused']);
  });

  it('piles messages up while the client stalls, counting them as buffered, and hands them over in order after', () => {
    const s = setup();
    s.clock.advance(0);
    s.t.setStalled(true);
    for (let i = 1; i <= 5; i++) s.peers[0].send(new Uint8Array(i * 100));
    s.clock.advance(10);
    expect(s.sizes).toEqual([]);
    expect(s.peers[0].bufferedAmount()).toBe(1500);
    s.t.setStalled(false);
    expect(s.sizes).toEqual([100, 200, 300, 400, 500]);
    expect(s.peers[0].bufferedAmount()).toBe(0);
  });

  it('tells the server a text frame from a binary one', () => {
    const s = setup({ latencyMs: 3 });
    s.t.sendText('{"hello":1}'); // before the handshake: kept for the server
    s.t.send(Uint8Array.of(4));
    s.clock.advance(6);
    expect([s.serverText, s.serverGot]).toEqual([['{"hello":1}'], [4]]);
  });

  it('closes with 1009 on an oversize client message as ws does, telling both ends once and dropping later sends', () => {
    const s = setup({ maxPayloadBytes: 16 });
    s.clock.advance(0);
    const closes: string[] = [];
    s.peers[0].onClose((code) => closes.push(`server ${code}`));
    s.t.send(Uint8Array.of(1));
    s.t.send(new Uint8Array(17));
    s.t.send(Uint8Array.of(2));
    s.clock.advance(1);
    expect(s.serverGot).toEqual([1]);
    expect(closes).toEqual(['server 1009']);
    expect(s.log).toEqual(['open@0', 'close 1009 Max payload size exceeded@0']);
    expect(s.peers[0].isOpen()).toBe(false);
  });

  it('names the peer with the label given to connect', () => {
    const clock = new ManualClock(0);
    const net = new MemoryNetwork(clock);
    const labels: string[] = [];
    net.listen('mem://a', (p) => labels.push(p.label));
    net.connect('mem://a', { open: () => {}, message: () => {}, close: () => {} }, 'ann');
    net.transport('mem://a', { open: () => {}, message: () => {}, close: () => {} });
    clock.advance(0);
    expect(labels).toEqual(['ann', 'memory#2 mem://a']);
  });
});
