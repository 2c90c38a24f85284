// Cost of checking one client frame: decodeClientMessage (structure scan, msgpack, validation) on the messages a
// playing client sends, against msgpackr's bare unpack of the same bytes, and on 20,000 generated hostile frames.
// With --against DIR (a checkout of another commit, e.g. `git worktree add /tmp/base main`), DIR's decoder runs in
// the same batches, so before/after share the machine's load. Prints ns per message.
// Run: node_modules/.bin/node bench/decode-client-message.ts [--rounds 15] [--against DIR]
import { Unpackr } from 'msgpackr';
import { join, resolve } from 'node:path';
import { pathToFileURL } from 'node:url';
import { decodeClientMessage, encodeClientMessage, PROTOCOL_VERSION, type ClientMessage } from '../shared/protocol/index.ts';
import { NEUTRAL_INPUT } from '../shared/sim/input.ts';
import { Prng } from '../shared/sim/prng.ts';
import { hostileFrame } from '../tests/helpers/hostile-frames.ts';

type Decode = (data: unknown) => unknown;

const argv = process.argv.slice(2);
const flag = (name: string): string | undefined => {
  const i = argv.indexOf(`--${name}`);
  return i >= 0 ? argv[i + 1] : undefined;
};
const rounds = Number(flag('rounds') ?? 15);
const againstDir = flag('against');
const against: Decode | null = againstDir
  ? ((await import(pathToFileURL(join(resolve(againstDir), 'shared/protocol/validation.ts')).href)) as { decodeClientMessage: Decode }).decodeClientMessage
  : null;
const perBatch = 100_000;

// msgpackr alone, with the options the protocol's codec has always used: the floor under any checking.
const bareUnpackr = new Unpackr({ useRecords: false, moreTypes: false, mapsAsObjects: true });
const bare: Decode = (bytes) => bareUnpackr.unpack(bytes as Uint8Array);

const walk = { ...NEUTRAL_INPUT, moveX: -90, moveZ: 127, yaw: 40_123, pitch: -1200, buttons: 4 };
/** What a client sends per second at 60 Hz with 30 Hz snapshots: 60 inputs (4 commands each), 30 acks, 1 ping. */
const MIX: ReadonlyArray<{ name: string; message: ClientMessage; perSecond: number }> = [
  { name: 'input x4', message: { type: 'input', firstTick: 123_456, commands: [walk, walk, { ...walk, buttons: 5 }, walk] }, perSecond: 60 },
  { name: 'ack', message: { type: 'ack', tick: 123_400 }, perSecond: 30 },
  { name: 'ping', message: { type: 'ping', clientTimeMs: 81_234.56789 }, perSecond: 1 },
  { name: 'hello', message: { type: 'hello', version: PROTOCOL_VERSION, name: 'Ada Lovelace', room: 'default' }, perSecond: 0 },
];

function timeNs(bytes: Uint8Array, fn: Decode): number {
  const start = process.hrtime.bigint();
  for (let i = 0; i < perBatch; i++) fn(bytes);
  return Number(process.hrtime.bigint() - start) / perBatch;
}

const median = (xs: number[]): number => [...xs].sort((a, b) => a - b)[xs.length >> 1];

/** Median ns of each decoder over `rounds` rounds, the order rotating so a burst of load hits every side. */
function compare(bytes: Uint8Array, sides: Array<[string, Decode]>): number[] {
  const samples = sides.map(() => [] as number[]);
  for (let r = 0; r < rounds; r++) {
    for (let k = 0; k < sides.length; k++) {
      const i = (k + r) % sides.length;
      samples[i].push(timeNs(bytes, sides[i][1]));
    }
  }
  return samples.map(median);
}

const sides: Array<[string, Decode]> = [['now', decodeClientMessage], ['bare', bare]];
if (against) sides.push(['against', against]);
let mixNow = 0;
let mixAgainst = 0;
for (const { name, message, perSecond } of MIX) {
  const bytes = encodeClientMessage(message);
  const check = decodeClientMessage(bytes);
  if (!check.ok) throw new Error(`${name} does not decode: ${check.error}`);
  const [now, floor, then] = compare(bytes, sides);
  mixNow += now * perSecond;
  mixAgainst += (then ?? 0) * perSecond;
  const vs = then === undefined ? '' : `, ${againstDir} ${then.toFixed(0).padStart(5)} ns (${now - then >= 0 ? '+' : ''}${(now - then).toFixed(0)} ns, ×${(now / then).toFixed(2)})`;
  console.log(`${name.padEnd(9)} ${String(bytes.length).padStart(3)} bytes: decodeClientMessage ${now.toFixed(0).padStart(5)} ns, bare msgpackr ${floor.toFixed(0).padStart(5)} ns${vs}`);
}
console.log(`one playing client (60 inputs + 30 acks + 1 ping per second): ${(mixNow / 1000).toFixed(1)} µs of CPU per client-second${against ? ` (${againstDir}: ${(mixAgainst / 1000).toFixed(1)} µs)` : ''}`);

// Hostile traffic: the generator the fuzz test uses. A decoder that throws is counted (each such frame once ended
// the whole server process).
const rng = new Prng(99);
const frames = Array.from({ length: 20_000 }, () => hostileFrame(rng, 1000).data);
function hostileNs(fn: Decode): { ns: number; threw: number } {
  let threw = 0;
  const start = process.hrtime.bigint();
  for (const f of frames) {
    try {
      fn(f);
    } catch {
      threw++;
    }
  }
  return { ns: Number(process.hrtime.bigint() - start) / frames.length, threw };
}
for (let r = 0; r < 3; r++) {
  const now = hostileNs(decodeClientMessage);
  const then = against ? hostileNs(against) : null;
  console.log(`20,000 hostile frames: ${now.ns.toFixed(0)} ns per frame, ${now.threw} threw${then ? `; ${againstDir}: ${then.ns.toFixed(0)} ns per frame, ${then.threw} threw` : ''}`);
}
