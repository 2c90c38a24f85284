// Room move: a `serve --room-workers 2 --record` process with a shape-rain 300 room and 4 SDK clients in it; the room
// is moved back and forth between the two workers over POST /api/rooms/ID/move, and each move's pause (from the
// old worker stopping the room to the new one taking it) is what the server answers. The clients must stay connected.
import { mkdtemp, rm } from 'node:fs/promises';
import { tmpdir } from 'node:os';
import { join } from 'node:path';
import { connect, type NetClient } from '../lib/client-lib.ts';
import { CLI_PATH, startNode, stopChild, waitForLine, type Child } from '../lib/child.ts';
import type { FigureImpl, FigureOutput, ReportRow } from '../lib/figure.ts';
import { median, round } from '../lib/stats.ts';

const URL_LINE = /serving .* at (http:\/\/\S+)/;
const ROOM = 'bench-move';
const CLIENTS = 4;

async function run(opts: { quick: boolean; log(m: string): void }): Promise<FigureOutput> {
  const moves = opts.quick ? 6 : 20;
  const dir = await mkdtemp(join(tmpdir(), 'taos-bench-move-'));
  let child: Child | null = null;
  const clients: NetClient[] = [];
  try {
    child = startNode(CLI_PATH, ['serve', '--port', '0', '--room-workers', '2', '--record', dir, '--log-level', 'warn', '--client-dir', '/nonexistent']);
    const url = (await waitForLine(child, URL_LINE, 30_000)).match[1];
    const created = await fetch(`${url}api/rooms`, { method: 'POST', body: JSON.stringify({ scenario: 'shape-rain', roomId: ROOM, params: { count: 300 } }) });
    if (created.status !== 201) throw new Error(`POST /api/rooms answered ${created.status}`);
    for (let i = 0; i < CLIENTS; i++) {
      const c = connect(url.replace(/^http/, 'ws'), { name: `mover${i}`, room: ROOM, reconnect: false });
      clients.push(c);
      await c.whenConnected();
      c.setInput({ moveX: 40 * i, moveZ: 100, yaw: 1000 * i, pitch: 0, buttons: 0 });
    }
    await new Promise((r) => setTimeout(r, 2000));
    opts.log(`room move: ${moves} moves of a shape-rain 300 room with ${CLIENTS} clients between 2 workers`);
    const pauses: number[] = [];
    const answers: number[] = [];
    for (let i = 0; i < moves; i++) {
      const t0 = performance.now();
      const res = await fetch(`${url}api/rooms/${ROOM}/move`, { method: 'POST' });
      answers.push(performance.now() - t0);
      if (res.status !== 200) throw new Error(`move ${i} answered ${res.status}: ${await res.text()}`);
      pauses.push(((await res.json()) as { move: { pauseMs: number } }).move.pauseMs);
      await new Promise((r) => setTimeout(r, 500));
    }
    const dropped = clients.filter((c) => c.stats().reconnects > 0 || c.state !== 'connected').length;
    if (dropped > 0) throw new Error(`${dropped} of ${CLIENTS} clients lost their connection across the moves`);
    const med = median(pauses);
    const max = Math.max(...pauses);
    const rows: ReportRow[] = [
      { figure: 'room move', measure: `players' pause per move, shape-rain 300 with ${CLIENTS} clients, --record (median of ${moves})`, value: med, unit: 'ms', digits: 1 },
      { figure: 'room move', measure: 'longest pause', value: max, unit: 'ms', digits: 1 },
      { figure: 'room move', measure: 'POST /api/rooms/ID/move answered after (median; includes building the new simulation)', value: median(answers), unit: 'ms', digits: 1 },
    ];
    return {
      headline: { roomMovePauseMs: round(med, 2) },
      detail: { moves, clients: CLIENTS, pauseMs: { median: round(med, 2), max: round(max, 2), all: pauses.map((p) => round(p, 1)) }, answerMs: { median: round(median(answers), 2) } },
      rows,
      charts: [],
      notes: [
        `One \`serve --room-workers 2 --record DIR\` process (durability tick); the room ${ROOM} (shape-rain, count 300) with ${CLIENTS} SDK clients sending inputs. Each move: the new worker builds the room's simulation first, then the old one stops the room between two ticks, hands over its checkpoint, input buffers and log, and the new one goes on; the pause is the server's own figure for that second part. Every client must still be connected with no reconnect afterwards.`,
      ],
    };
  } finally {
    for (const c of clients) c.close();
    if (child) await stopChild(child);
    await rm(dir, { recursive: true, force: true });
  }
}

/** The room move figure. */
export const figure: FigureImpl = { run };
