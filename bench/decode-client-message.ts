// Cost of checking one client frame: decodeClientMessage (scan, msgpack, validation) against msgpackr's bare unpack
// of the same bytes, on the messages a playing client sends, in alternating batches. Prints ns per message.
// Run: node_modules/.bin/node bench/decode-client-message.ts [ROUNDS]
import { Unpackr } from 'msgpackr';
import { decodeClientMessage, encodeClientMessage, type ClientMessage } from '../shared/protocol/index.ts';
import { NEUTRAL_INPUT } from '../shared/sim/input.ts';

// msgpackr alone, with the options the protocol's codec has always used: the floor under any checking.
const bareUnpackr = new Unpackr({ useRecords: false, moreTypes: false, mapsAsObjects: true });
const unpackFrame = (bytes: Uint8Array): unknown => bareUnpackr.unpack(bytes);

const rounds = Number(process.argv[2] ?? 15);
const perBatch = 200_000;

const walk = { ...NEUTRAL_INPUT, moveX: -90, moveZ: 127, yaw: 40_123, pitch: -1200, buttons: 4 };
/** What a client sends per second at 60 Hz with 30 Hz snapshots: 60 inputs (4 commands each), 30 acks, 1 ping. */
const MIX: ReadonlyArray<{ name: string; message: ClientMessage; perSecond: number }> = [
  { name: 'input x4', message: { type: 'input', firstTick: 123_456, commands: [walk, walk, { ...walk, buttons: 5 }, walk] }, perSecond: 60 },
  { name: 'ack', message: { type: 'ack', tick: 123_400 }, perSecond: 30 },
  { name: 'ping', message: { type: 'ping', clientTimeMs: 81_234.56789 }, perSecond: 1 },
  { name: 'hello', message: { type: 'hello', version: 1, name: 'Ada Lovelace', room: 'default' }, perSecond: 0 },
];

function timeNs(bytes: Uint8Array, fn: (b: Uint8Array) => unknown): number {
  let sink = 0;
  const start = process.hrtime.bigint();
  for (let i = 0; i < perBatch; i++) if (fn(bytes) !== undefined) sink++;
  const ns = Number(process.hrtime.bigint() - start) / perBatch;
  if (sink !== perBatch) throw new Error('a decode returned undefined');
  return ns;
}

const median = (xs: number[]): number => [...xs].sort((a, b) => a - b)[xs.length >> 1];

const rows: Array<{ name: string; bytes: number; checkedNs: number; bareNs: number; perSecond: number }> = [];
for (const { name, message, perSecond } of MIX) {
  const bytes = encodeClientMessage(message);
  const check = decodeClientMessage(bytes);
  if (!check.ok) throw new Error(`${name} does not decode: ${check.error}`);
  const checked: number[] = [];
  const bare: number[] = [];
  for (let r = 0; r < rounds; r++) {
    // Alternate the order so a burst of load from elsewhere hits both sides.
    if (r % 2 === 0) {
      checked.push(timeNs(bytes, decodeClientMessage));
      bare.push(timeNs(bytes, unpackFrame));
    } else {
      bare.push(timeNs(bytes, unpackFrame));
      checked.push(timeNs(bytes, decodeClientMessage));
    }
  }
  rows.push({ name, bytes: bytes.length, checkedNs: median(checked), bareNs: median(bare), perSecond });
}

for (const r of rows) {
  console.log(`${r.name.padEnd(9)} ${String(r.bytes).padStart(3)} bytes: decodeClientMessage ${r.checkedNs.toFixed(0).padStart(5)} ns, bare unpack ${r.bareNs.toFixed(0).padStart(5)} ns, checks ${(r.checkedNs - r.bareNs).toFixed(0).padStart(5)} ns`);
}
const weight = rows.reduce((n, r) => n + r.perSecond, 0);
const mixed = rows.reduce((n, r) => n + r.checkedNs * r.perSecond, 0) / weight;
const perClientUs = rows.reduce((n, r) => n + r.checkedNs * r.perSecond, 0) / 1000;
console.log(`mix of one playing client (60 inputs + 30 acks + 1 ping per second): ${mixed.toFixed(0)} ns per message, ${perClientUs.toFixed(1)} µs of CPU per client-second`);
