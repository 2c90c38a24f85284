// Headless scripted bots over the network: N clients of the client library (sdk/) join a server, each driven
// by its own seeded BotScript (walk, strafe, turn, sprint, jump, fire) at 60 commands per second, and report traffic.
import { connect, type NetClient, type PredictionStats, type PredictOptions, type TransportFactory } from '../sdk/index.ts';
import type { Clock, TimerHandle } from '../shared/clock.ts';
import { BotScript } from '../shared/sim/bots.ts';
import { NEUTRAL_INPUT } from '../shared/sim/input.ts';
import { SystemClock } from '../server/clock.ts';
import { TICK_MS } from '../shared/tick-rate.ts';

/** Options of runBots. */
export interface BotsOptions {
  /** ws:// URL of the server. */
  url: string;
  count: number;
  /** Room id; null: the server's default room. */
  room?: string | null;
  /** Stop after this many seconds; null: run until stop() (or a signal in the CLI). */
  seconds?: number | null;
  /** Seed of the bots' scripts (bot i uses `${seed}-${i}`). Default 1. */
  seed?: number | string;
  /** Milliseconds between two bots connecting. Default 100. */
  joinSpacingMs?: number;
  clock?: Clock;
  /** Transport for the client library; default the global WebSocket. */
  transport?: TransportFactory;
  /** Progress lines (every 5 s). */
  progress?: (line: string) => void;
  /** Predicted play (bots run the simulation themselves in rooms that offer predict mode). */
  predict?: PredictOptions;
}

/** One bot's outcome. */
export interface BotReport {
  name: string;
  playerId: number | null;
  connected: boolean;
  /** How the client ended: 'client-closed' after a normal stop, else the server's reason. */
  closedReason: string | null;
  /** The server's words for that ending (e.g. "room-full: room default is full (32 clients)"); null while open. */
  closedDetail: string | null;
  snapshots: number;
  bytesIn: number;
  bytesOut: number;
  rttMs: number | null;
  missedInputTicks: number | null;
  serverErrors: number;
  /** Predicted play's numbers at the end (null: the bot did not predict). */
  prediction: PredictionStats | null;
}

/** The run's outcome. */
export interface BotsReport {
  seconds: number;
  bots: BotReport[];
  /** Mean kbps received per bot over the run. */
  kbpsInPerBot: number;
}

/** A running crowd; stop() ends it early. */
export interface BotsRun {
  done: Promise<BotsReport>;
  stop(): void;
}

/** Starts `count` bots; resolves when the time is up (or stop() is called) with a per-bot report. */
export function startBots(opts: BotsOptions): BotsRun {
  if (!Number.isInteger(opts.count) || opts.count < 1 || opts.count > 1000) throw new Error(`bots: count must be an integer in [1, 1000], got ${opts.count}`);
  if (opts.seconds !== undefined && opts.seconds !== null && !(opts.seconds > 0)) throw new Error(`bots: seconds must be > 0, got ${opts.seconds}`);
  const clock = opts.clock ?? new SystemClock();
  const seed = opts.seed ?? 1;
  const spacing = opts.joinSpacingMs ?? 100;
  const startedMs = clock.nowMs();
  const bots: Array<{ name: string; client: NetClient | null; script: BotScript; errors: number; connected: boolean }> = [];
  const timers = new Set<TimerHandle>();
  let stopped = false;
  let finish: () => void = () => {};
  const done = new Promise<BotsReport>((resolve) => {
    finish = () => {
      for (const t of timers) clock.clearTimer(t);
      timers.clear();
      for (const b of bots) b.client?.close();
      const seconds = (clock.nowMs() - startedMs) / 1000;
      const reports = bots.map((b): BotReport => {
        const s = b.client?.stats();
        return {
          name: b.name,
          playerId: b.client?.playerId ?? null,
          connected: b.connected,
          closedReason: b.client?.closed?.reason ?? null,
          closedDetail: b.client?.closed?.detail ?? null,
          snapshots: s?.snapshots ?? 0,
          bytesIn: s?.bytesIn ?? 0,
          bytesOut: s?.bytesOut ?? 0,
          rttMs: s?.rttMs ?? null,
          missedInputTicks: s?.missedInputTicks ?? null,
          serverErrors: b.errors,
          prediction: s?.prediction ?? null,
        };
      });
      const totalIn = reports.reduce((a, r) => a + r.bytesIn, 0);
      resolve({ seconds, bots: reports, kbpsInPerBot: seconds > 0 ? (totalIn * 8) / 1000 / seconds / reports.length : 0 });
    };
  });
  const later = (ms: number, fn: () => void): void => {
    const t = clock.setTimer(ms, () => {
      timers.delete(t);
      fn();
    });
    timers.add(t);
  };

  for (let i = 0; i < opts.count; i++) {
    const bot = { name: `bot-${i + 1}`, client: null as NetClient | null, script: new BotScript({ seed: `${String(seed)}-${i}`, bots: 1 }), errors: 0, connected: false };
    bots.push(bot);
    later(i * spacing, () => {
      if (stopped) return;
      const client = connect(opts.url, { name: bot.name, room: opts.room ?? null, clock, transport: opts.transport, predict: opts.predict });
      bot.client = client;
      client.on('welcome', () => (bot.connected = true));
      client.on('serverError', () => bot.errors++);
      // 60 commands per second from the bot's script; the client library stamps and sends them ahead of the server.
      const drive = (): void => {
        if (stopped || client.state === 'closed') return;
        const rec = bot.script.next();
        client.setInput(rec.commands[0]?.input ?? NEUTRAL_INPUT);
        later(TICK_MS, drive);
      };
      drive();
    });
  }
  if (opts.progress) {
    const report = (): void => {
      if (stopped) return;
      const live = bots.filter((b) => b.client?.state === 'connected').length;
      const kbps = bots.reduce((a, b) => a + (b.client?.stats().kbpsIn ?? 0), 0);
      const rtts = bots.map((b) => b.client?.stats().rttMs).filter((r): r is number => typeof r === 'number');
      const rtt = rtts.length ? rtts.reduce((a, b) => a + b, 0) / rtts.length : null;
      opts.progress?.(`${((clock.nowMs() - startedMs) / 1000).toFixed(0)} s: ${live}/${bots.length} bots connected, ${kbps.toFixed(0)} kbps in total${rtt === null ? '' : `, rtt ${rtt.toFixed(1)} ms`}`);
      later(5000, report);
    };
    later(5000, report);
  }
  const stop = (): void => {
    if (stopped) return;
    stopped = true;
    finish();
  };
  if (opts.seconds) later(opts.seconds * 1000, stop);
  return { done, stop };
}
