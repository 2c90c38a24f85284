// A loopback link conditioner: a TCP proxy on 127.0.0.1 port 0 in front of a server that holds every chunk, each way,
// for a seeded one-way delay with jitter and turns a fraction of chunks into "lost" ones. A WebSocket rides on TCP,
// so a lost segment is modelled as TCP sees it: resent after a retransmit timeout, holding back everything behind it
// (every chunk leaves no earlier than the one before it: order is kept, as on the wire).
import { createServer, connect, type Server, type Socket } from 'node:net';
import type { AddressInfo } from 'node:net';
import { Prng } from '../../shared/sim/prng.ts';

/** How the link misbehaves, each way. */
export interface LinkShape {
  delayMs: number;
  jitterMs: number;
  /** Fraction of chunks lost once (then resent). */
  lossRate: number;
  /** Extra delay of a lost chunk (its retransmit). */
  retransmitMs: number;
  seed: number;
}

/** A running conditioner. */
export interface LinkConditioner {
  /** host:port clients should use instead of the server's. */
  readonly port: number;
  /** Chunks carried and chunks "lost" (delayed by a retransmit), both directions. */
  counts(): { chunks: number; lost: number };
  close(): Promise<void>;
}

/** Starts a conditioner forwarding to `targetPort` on 127.0.0.1. */
export async function startLinkConditioner(targetPort: number, shape: LinkShape): Promise<LinkConditioner> {
  const rng = new Prng(shape.seed);
  const sockets = new Set<Socket>();
  const timers = new Set<NodeJS.Timeout>();
  let chunks = 0;
  let lost = 0;
  // One direction: a queue drained in order by one timer (timers of different delays may fire out of order), each
  // chunk leaving after its own delay but never before the one ahead of it; the end follows the last chunk.
  const pipe = (from: Socket, to: Socket): void => {
    const queue: Array<{ dueMs: number; chunk: Buffer | null }> = [];
    let timer: NodeJS.Timeout | null = null;
    let lastDueMs = 0;
    const drain = (): void => {
      if (timer) timers.delete(timer);
      timer = null;
      const nowMs = performance.now();
      while (queue.length > 0 && queue[0].dueMs <= nowMs) {
        const { chunk } = queue.shift()!;
        if (to.destroyed) continue;
        if (chunk === null) to.end();
        else to.write(chunk);
      }
      if (queue.length > 0) {
        timer = setTimeout(drain, Math.max(1, queue[0].dueMs - nowMs));
        timers.add(timer);
      }
    };
    const enqueue = (chunk: Buffer | null, delayMs: number): void => {
      lastDueMs = Math.max(lastDueMs, performance.now() + delayMs);
      queue.push({ dueMs: lastDueMs, chunk });
      if (timer === null) drain();
    };
    from.on('data', (chunk: Buffer) => {
      chunks++;
      let delayMs = shape.delayMs + (rng.next() * 2 - 1) * shape.jitterMs;
      if (rng.next() < shape.lossRate) {
        lost++;
        delayMs += shape.retransmitMs;
      }
      enqueue(chunk, delayMs);
    });
    from.on('end', () => enqueue(null, 0));
    from.on('error', () => to.destroy());
  };
  const server: Server = createServer((client) => {
    const upstream = connect(targetPort, '127.0.0.1');
    for (const s of [client, upstream]) {
      sockets.add(s);
      s.on('close', () => sockets.delete(s));
    }
    pipe(client, upstream);
    pipe(upstream, client);
  });
  await new Promise<void>((resolve) => server.listen(0, '127.0.0.1', resolve));
  return {
    port: (server.address() as AddressInfo).port,
    counts: () => ({ chunks, lost }),
    async close() {
      for (const t of timers) clearTimeout(t);
      timers.clear();
      for (const s of sockets) s.destroy();
      await new Promise<void>((resolve) => server.close(() => resolve()));
    },
  };
}
