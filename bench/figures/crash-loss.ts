// Ticks lost at kill -9, per --durability mode: a real `serve --record` process with two client-library bots walking
// in the default room is killed with SIGKILL after a seeded 1–2.5 s of play; the loss is how many ticks a bot had
// already seen applied (snapshot or event ticks) that are missing from the log on disk.
import { mkdtemp, readdir, readFile, rm } from 'node:fs/promises';
import { tmpdir } from 'node:os';
import { join } from 'node:path';
import { readLogBytes } from '../../server/log/index.ts';
import { DURABILITY_MODES, type DurabilityMode } from '../../server/recorder.ts';
import { connect, type NetClient } from '../../sdk/client.ts';
import { NEUTRAL_INPUT } from '../../shared/sim/input.ts';
import { CLI_PATH, startNode, waitForLine } from '../lib/child.ts';
import type { FigureImpl, FigureOutput, ReportRow } from '../lib/figure.ts';
import { round } from '../lib/stats.ts';

/** One kill: the highest tick a bot saw, the ticks on disk, and the seen ticks missing from the log. */
interface Kill {
  seenTick: number;
  durableTicks: number;
  lostSeenTicks: number;
}

async function killOnce(mode: DurabilityMode, dir: string, playMs: number): Promise<Kill> {
  const child = startNode(CLI_PATH, ['serve', '--port', '0', '--record', dir, '--durability', mode, '--log-level', 'warn']);
  const exited = new Promise<void>((done) => child.proc.on('exit', () => done()));
  const clients: NetClient[] = [];
  let seen = -1;
  let steering: NodeJS.Timeout | null = null;
  try {
    const { match } = await waitForLine(child, /(ws:\/\/\S+\/)/, 30_000);
    for (const name of ['ann', 'bob']) {
      const c = connect(match[1], { name, reconnect: false });
      c.on('snapshot', (s) => (seen = Math.max(seen, s.tick)));
      c.on('events', (events) => events.forEach((e) => (seen = Math.max(seen, e.tick))));
      clients.push(c);
    }
    await Promise.all(clients.map((c) => c.whenConnected()));
    let step = 0;
    steering = setInterval(() => {
      step++;
      for (const c of clients) if (c.state === 'connected') c.setInput({ ...NEUTRAL_INPUT, moveZ: 127, yaw: (step * 997) % 65536, buttons: step % 20 === 0 ? 1 : 0 });
    }, 50);
    await new Promise((r) => setTimeout(r, playMs));
    child.proc.kill('SIGKILL');
    await exited;
  } finally {
    if (steering) clearInterval(steering);
    for (const c of clients) c.close();
    child.proc.kill('SIGKILL');
  }
  const file = (await readdir(dir)).find((f) => f.endsWith('.taoslog'));
  if (!file) throw new Error(`crash-loss: no log in ${dir}`);
  const durableTicks = readLogBytes(new Uint8Array(await readFile(join(dir, file)))).outcome.ticks;
  return { seenTick: seen, durableTicks, lostSeenTicks: Math.max(0, seen + 1 - durableTicks) };
}

async function run(opts: { quick: boolean; log(m: string): void }): Promise<FigureOutput> {
  const kills = opts.quick ? 2 : 3;
  const root = await mkdtemp(join(tmpdir(), 'taos-bench-crash-'));
  const byMode = new Map<DurabilityMode, Kill[]>(DURABILITY_MODES.map((m) => [m, []]));
  try {
    for (let k = 0; k < kills; k++) {
      for (const mode of DURABILITY_MODES) {
        const playMs = 1000 + ((k * 7919 + mode.length * 104729) % 1500);
        opts.log(`kill ${k + 1}/${kills} with --durability ${mode} after ${playMs} ms of play`);
        byMode.get(mode)!.push(await killOnce(mode, join(root, `${mode}-${k}`), playMs));
      }
    }
  } finally {
    await rm(root, { recursive: true, force: true });
  }
  const headline: Record<string, number | null> = {};
  const detail: Record<string, unknown> = { kills, bots: 2 };
  const rows: ReportRow[] = [];
  for (const mode of DURABILITY_MODES) {
    const list = byMode.get(mode)!;
    const worst = Math.max(...list.map((k) => k.lostSeenTicks));
    detail[mode] = { kills: list, worstLostSeenTicks: worst, meanLostSeenTicks: round(list.reduce((n, k) => n + k.lostSeenTicks, 0) / list.length, 1) };
    headline[`crashLostTicks${mode[0].toUpperCase()}${mode.slice(1)}`] = worst;
    rows.push({ figure: 'crash loss', measure: `--durability ${mode}: seen ticks missing after kill -9 (worst of ${kills})`, value: worst, unit: 'ticks', digits: 0, ...(mode === 'tick' ? { goal: { op: '<=' as const, value: 0 } } : {}) });
  }
  return {
    headline,
    detail,
    rows,
    charts: [{ title: 'Ticks a client saw that a kill -9 lost (worst kill)', unit: 'ticks', bars: DURABILITY_MODES.map((m) => ({ label: m, value: (detail[m] as { worstLostSeenTicks: number }).worstLostSeenTicks, series: m === 'tick' ? ('ours' as const) : ('other' as const) })) }],
    notes: [`${kills} kill(s) per mode; each kill starts a fresh \`serve --record\` process (default room, character-course) with two client-library bots. Lost = (highest tick a bot saw in a snapshot or event) + 1 − (tick records in the log after the kill), floored at 0.`],
  };
}

/** The crash-loss figure. */
export const figure: FigureImpl = { run };
