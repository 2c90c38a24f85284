// Fleet redirect: two `serve --redis` processes on a loopback redis-server; a room lives on A. Time from connect() to
// the welcome for an SDK client that asks A for it (direct) and one that asks B and is sent on to A (redirected:
// B looks the room up in Redis, answers error + bye room-moved, the client opens a second socket to A), alternated.
import { connect } from '../lib/client-lib.ts';
import { redisMissingReason, startRedisServer, type RedisServer } from '../../tests/helpers/redis-process.ts';
import { CLI_PATH, startNode, stopChild, waitForLine, type Child } from '../lib/child.ts';
import type { FigureImpl, FigureOutput, ReportRow } from '../lib/figure.ts';
import { median, quantile, round } from '../lib/stats.ts';

const URL_LINE = /serving .* at (http:\/\/\S+)/;
const ROOM = 'bench-arena';

async function serveMember(redisUrl: string): Promise<{ child: Child; url: string }> {
  const child = startNode(CLI_PATH, ['serve', '--port', '0', '--redis', redisUrl, '--log-level', 'warn', '--client-dir', '/nonexistent']);
  const { match } = await waitForLine(child, URL_LINE, 30_000);
  return { child, url: match[1] };
}

/** ms from connect() to the welcome; checks the client ended on `expectUrl`. */
async function joinOnce(wsUrl: string, expectUrl: string, i: number): Promise<number> {
  const t0 = performance.now();
  const client = connect(wsUrl, { name: `bench${i}`, room: ROOM, reconnect: false });
  try {
    await client.whenConnected();
    const ms = performance.now() - t0;
    if (client.url !== expectUrl) throw new Error(`the client ended on ${client.url}, not ${expectUrl}`);
    return ms;
  } finally {
    client.close();
  }
}

async function run(opts: { quick: boolean; log(m: string): void }): Promise<FigureOutput> {
  const missing = redisMissingReason();
  if (missing) {
    return { headline: { redirectWelcomeMs: null }, detail: { skipped: missing }, rows: [], charts: [], notes: [`Not measured: ${missing}.`] };
  }
  const samples = opts.quick ? 20 : 60;
  let redis: RedisServer | null = null;
  const children: Child[] = [];
  try {
    redis = await startRedisServer();
    const a = await serveMember(redis.url);
    children.push(a.child);
    const b = await serveMember(redis.url);
    children.push(b.child);
    const created = await fetch(`${a.url}api/rooms`, { method: 'POST', body: JSON.stringify({ scenario: 'character-course', roomId: ROOM }) });
    if (created.status !== 201) throw new Error(`POST /api/rooms on A answered ${created.status}`);
    const aWs = a.url.replace(/^http/, 'ws');
    const bWs = b.url.replace(/^http/, 'ws');
    // Warm both paths (JIT, Redis connection, the room's first joins) before timing.
    for (let i = 0; i < 3; i++) {
      await joinOnce(aWs, aWs, i);
      await joinOnce(bWs, aWs, i);
    }
    opts.log(`fleet redirect: ${samples} direct and ${samples} redirected joins, alternated`);
    const direct: number[] = [];
    const redirected: number[] = [];
    for (let i = 0; i < samples; i++) {
      if (i % 2 === 0) {
        direct.push(await joinOnce(aWs, aWs, i));
        redirected.push(await joinOnce(bWs, aWs, i));
      } else {
        redirected.push(await joinOnce(bWs, aWs, i));
        direct.push(await joinOnce(aWs, aWs, i));
      }
    }
    const med = { direct: median(direct), redirected: median(redirected) };
    const p99 = { direct: quantile(direct, 0.99), redirected: quantile(redirected, 0.99) };
    const rows: ReportRow[] = [
      { figure: 'fleet redirect', measure: `connect → welcome, asking the hosting server (median of ${samples})`, value: med.direct, unit: 'ms', digits: 1 },
      { figure: 'fleet redirect', measure: `connect → welcome, asking another server: room-moved, then the host (median of ${samples})`, value: med.redirected, unit: 'ms', digits: 1 },
      { figure: 'fleet redirect', measure: 'p99 redirected', value: p99.redirected, unit: 'ms', digits: 1 },
    ];
    return {
      headline: { redirectWelcomeMs: round(med.redirected, 2) },
      detail: {
        samples,
        directMs: { median: round(med.direct, 2), p99: round(p99.direct, 2) },
        redirectedMs: { median: round(med.redirected, 2), p99: round(p99.redirected, 2) },
        redirectCostMs: round(med.redirected - med.direct, 2),
      },
      rows,
      charts: [
        {
          title: 'Fleet: connect → welcome (ms, median)',
          unit: 'ms',
          bars: [
            { label: 'asking the host', value: med.direct, series: 'baseline' },
            { label: 'asking another server (redirected)', value: med.redirected, series: 'ours' },
          ],
        },
      ],
      notes: [
        `Two \`serve --redis\` processes and a redis-server on loopback; the room ${ROOM} (character-course) lives on A. Each sample is a fresh SDK client (connect(), whenConnected(), close()) with the global WebSocket; direct asks A, redirected asks B, which looks the room up in Redis and answers error + bye room-moved with A's URL, and the client opens a new socket to A. ${samples} of each, alternated, after 3 warm-up pairs. Loopback only: a real network adds one round trip per extra connection.`,
      ],
    };
  } finally {
    await Promise.all(children.map((c) => stopChild(c)));
    await redis?.stop();
  }
}

/** The fleet redirect figure. */
export const figure: FigureImpl = { run };
