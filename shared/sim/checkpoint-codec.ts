// The checkpoint byte form: a versioned, self-describing container (magic, version, the setup it belongs to, tagged
// sections, a 64-bit checksum) around the JS state, body records, Jolt's SaveState(All) bytes and the characters.
import { restoreStateBytes, saveStateBytes, type SensorEvent } from '../physics/index.ts';
import type { BodyRecord } from './body-registry.ts';
import type { Bullet } from './bullets.ts';
import { ByteReader, ByteWriter } from '../byte-io.ts';
import { restoreData, type CheckpointData } from './checkpoint.ts';
import { hasGameSection, readGameSection, TAG_GAME, writeGameSection } from './game-section.ts';
import { CHARACTER_SHAPE, type PlayerSnapshot } from './players.ts';
import { readRecord, recordBytes, writeRecord } from './recipe-codec.ts';
import type { SimCore } from './sim-core.ts';
import { Hasher64 } from './state-hash.ts';

/** The first 8 bytes of every byte checkpoint. */
export const CHECKPOINT_MAGIC = 'TAOSCKPT';
/** The format version this build writes and reads. */
export const CHECKPOINT_FORMAT_VERSION = 1;

const TAG_STATE = 0x54415453; // 'STAT'
const TAG_BODIES = 0x59444f42; // 'BODY'
const TAG_JOLT = 0x544c4f4a; // 'JOLT'
const TAG_CHARACTERS = 0x52414843; // 'CHAR'

function checksum(bytes: Uint8Array, end: number): [number, number] {
  const h = new Hasher64(0x636b7074);
  const whole = end >>> 2;
  const aligned = new Uint8Array(whole * 4);
  aligned.set(bytes.subarray(0, whole * 4));
  h.words(new Uint32Array(aligned.buffer));
  for (let i = whole * 4; i < end; i++) h.word(bytes[i]);
  const hex = h.hex();
  return [parseInt(hex.slice(0, 8), 16), parseInt(hex.slice(8), 16)];
}

function section(w: ByteWriter, tag: number, body: () => void): void {
  w.u32(tag);
  const at = w.length;
  w.u32(0);
  body();
  w.patchU32(at, w.length - at - 4);
}

function writeSetup(w: ByteWriter, core: SimCore): void {
  w.u32PrefixedString(core.def.name);
  const names = Object.keys(core.params).sort();
  w.u32(names.length);
  for (const n of names) w.u32PrefixedString(n).f64(core.params[n]);
  if (typeof core.seed === 'string') w.u8(1).u32PrefixedString(core.seed);
  else w.u8(0).u32(core.seed);
}

function writeState(w: ByteWriter, d: CheckpointData): void {
  w.u32(d.tick).u32s(d.prng).u32(d.joinCount).u32(d.nextBodyId).u32(d.constraintCount);
  w.u32(d.slots.highWater).u32s(d.slots.free).u32PrefixedBytes(d.slots.sequences);
  w.u32(d.players.length);
  for (const p of d.players) {
    w.u32(p.playerId).u32PrefixedString(p.name).u32(p.joinIndex).u32(p.bodyId).u32(p.joltId);
    w.i32(p.input.moveX).i32(p.input.moveZ).i32(p.input.yaw).i32(p.input.pitch).i32(p.input.buttons).f64(p.nextFireTick);
  }
  w.u32(d.bullets.length);
  for (const b of d.bullets) w.u32(b.bodyId).u32(b.ownerId).f64(b.expireTick);
  w.u8(d.scenarioState ? 1 : 0);
  if (d.scenarioState) w.f64s(d.scenarioState);
  w.u32s(d.overlaps);
  w.u32(d.carriedSensor.length);
  for (const e of d.carriedSensor) w.u8(e.kind === 'enter' ? 1 : 0).u32(e.sensorId).u32(e.otherId);
}

/** Encodes a checkpoint of `core` (data from captureData) with Jolt's state as bytes. */
export function encodeCheckpoint(core: SimCore, d: CheckpointData): Uint8Array {
  const J = core.world.jolt;
  const w = new ByteWriter(4096);
  for (let i = 0; i < CHECKPOINT_MAGIC.length; i++) w.u8(CHECKPOINT_MAGIC.charCodeAt(i));
  w.u32(CHECKPOINT_FORMAT_VERSION);
  writeSetup(w, core);
  section(w, TAG_STATE, () => writeState(w, d));
  section(w, TAG_BODIES, () => {
    w.u32(d.records.length);
    for (const r of d.records) writeRecord(w, r);
  });
  section(w, TAG_JOLT, () => w.u32PrefixedBytes(saveStateBytes(J, (r) => core.world.system.SaveState(r, J.EStateRecorderState_All))));
  section(w, TAG_CHARACTERS, () => {
    w.u32(d.characterStates.size);
    for (const [id, bytes] of d.characterStates) w.u32(id).u32PrefixedBytes(bytes);
  });
  if (hasGameSection(core)) section(w, TAG_GAME, () => writeGameSection(w, d));
  const [a, b] = checksum(w.finish(), w.length);
  w.u32(a).u32(b);
  return w.finish();
}

function readSetup(r: ByteReader, core: SimCore): void {
  const name = r.u32PrefixedString('scenario name');
  const params: Record<string, number> = {};
  const n = r.count('parameter count', 12);
  for (let i = 0; i < n; i++) params[r.u32PrefixedString('parameter name')] = r.f64('parameter value');
  const seed: number | string = r.u8('seed kind') === 1 ? r.u32PrefixedString('seed') : r.u32('seed');
  const mine = Object.keys(core.params).sort();
  const theirs = Object.keys(params).sort();
  const sameParams = mine.length === theirs.length && mine.every((k, i) => k === theirs[i] && Object.is(core.params[k], params[k]));
  if (name !== core.def.name || !sameParams || seed !== core.seed) {
    throw new Error(
      `restoreCheckpointBytes: the checkpoint is for ${name} ${JSON.stringify(params)} seed ${JSON.stringify(seed)}, ` +
        `this simulation runs ${core.def.name} ${JSON.stringify(core.params)} seed ${JSON.stringify(core.seed)}`,
    );
  }
}

function readState(r: ByteReader): Omit<CheckpointData, 'records' | 'characterStates'> {
  const tick = r.u32('tick');
  const prng = r.u32s('prng');
  if (prng.length !== 4) throw new Error('checkpoint: PRNG state must have 4 words');
  const joinCount = r.u32('join count');
  const nextBodyId = r.u32('next body id');
  const constraintCount = r.u32('constraint count');
  const slots = { highWater: r.u32('slot high water'), free: r.u32s('free slots'), sequences: r.u32PrefixedBytes('slot sequences') };
  const players: PlayerSnapshot[] = [];
  const np = r.count('player count', 45);
  for (let i = 0; i < np; i++) {
    const playerId = r.u32('player id');
    const name = r.u32PrefixedString('player name');
    const joinIndex = r.u32('join index');
    const bodyId = r.u32('character body id');
    const joltId = r.u32('character jolt id');
    const input = { moveX: r.i32('moveX'), moveZ: r.i32('moveZ'), yaw: r.i32('yaw'), pitch: r.i32('pitch'), buttons: r.i32('buttons') };
    players.push({ playerId, name, joinIndex, bodyId, joltId, input, nextFireTick: r.f64('next fire tick') });
  }
  const bullets: Bullet[] = [];
  const nb = r.count('bullet count', 16);
  for (let i = 0; i < nb; i++) bullets.push({ bodyId: r.u32('bullet body'), ownerId: r.u32('bullet owner'), expireTick: r.f64('bullet expiry') });
  const scenarioState = r.u8('scenario state flag') ? r.f64s('scenario state') : null;
  const overlaps = r.u32s('sensor overlaps');
  const carriedSensor: SensorEvent[] = [];
  const ne = r.count('carried sensor events', 9);
  for (let i = 0; i < ne; i++) carriedSensor.push({ kind: r.u8('event kind') === 1 ? 'enter' : 'exit', sensorId: r.u32('sensor id'), otherId: r.u32('other id') });
  return { tick, prng, joinCount, nextBodyId, constraintCount, slots, players, bullets, scenarioState, gameState: [], overlaps, carriedSensor };
}

function expectSection(r: ByteReader, tag: number, name: string): ByteReader {
  const got = r.u32(`${name} section tag`);
  if (got !== tag) throw new Error(`checkpoint: expected the ${name} section, found tag 0x${got.toString(16)}`);
  const len = r.u32(`${name} section length`);
  const start = r.offset;
  r.raw(len, `${name} section`);
  return new ByteReader(r.bytes, start, start + len, `checkpoint ${name} section`);
}

/** Decodes a byte checkpoint and restores it into `core` (same scenario, params and seed). */
export function decodeCheckpoint(core: SimCore, bytes: Uint8Array): void {
  if (!(bytes instanceof Uint8Array)) throw new Error('restoreCheckpointBytes: expected a Uint8Array');
  if (bytes.length < CHECKPOINT_MAGIC.length + 12) throw new Error('restoreCheckpointBytes: too short to be a checkpoint');
  for (let i = 0; i < CHECKPOINT_MAGIC.length; i++) {
    if (bytes[i] !== CHECKPOINT_MAGIC.charCodeAt(i)) throw new Error('restoreCheckpointBytes: not a taos-physics checkpoint (bad magic)');
  }
  const r = new ByteReader(bytes, CHECKPOINT_MAGIC.length, bytes.length - 8, 'checkpoint');
  const version = r.u32('format version');
  if (version !== CHECKPOINT_FORMAT_VERSION) throw new Error(`restoreCheckpointBytes: format version ${version}, this build reads ${CHECKPOINT_FORMAT_VERSION}`);
  const [a, b] = checksum(bytes, bytes.length - 8);
  const tail = new DataView(bytes.buffer, bytes.byteOffset + bytes.length - 8, 8);
  if (tail.getUint32(0, true) !== a || tail.getUint32(4, true) !== b) throw new Error('restoreCheckpointBytes: checksum mismatch (the bytes are corrupt)');
  readSetup(r, core);
  const state = readState(expectSection(r, TAG_STATE, 'state'));
  const joinIndex = new Map(state.players.map((p) => [p.playerId, p.joinIndex]));
  const br = expectSection(r, TAG_BODIES, 'bodies');
  const records: BodyRecord[] = [];
  const nr = br.count('body count', 9);
  for (let i = 0; i < nr; i++) {
    records.push(readRecord(br, { sceneRecord: (id) => core.buildRecords.get(id), characterShape: CHARACTER_SHAPE, joinIndexOf: (id) => joinIndex.get(id) }));
  }
  for (let i = 1; i < records.length; i++) if (records[i].id <= records[i - 1].id) throw new Error('checkpoint: body records are not in ascending id order');
  const jolt = expectSection(r, TAG_JOLT, 'jolt').u32PrefixedBytes('jolt state');
  const cr = expectSection(r, TAG_CHARACTERS, 'characters');
  const characterStates = new Map<number, Uint8Array>();
  const nc = cr.count('character count', 8);
  for (let i = 0; i < nc; i++) characterStates.set(cr.u32('character player'), cr.u32PrefixedBytes('character state'));
  if (hasGameSection(core)) state.gameState = readGameSection(expectSection(r, TAG_GAME, 'game'), state.players, core);
  else if (r.remaining > 0) throw new Error('checkpoint: a game section, but this scenario declares no game input or state');
  const data: CheckpointData = { ...state, records, characterStates };
  const J = core.world.jolt;
  const same = (live: BodyRecord, saved: BodyRecord): boolean => {
    if (live === saved) return true;
    if (live.kind !== saved.kind || live.kind === 'scene') return false;
    const x = recordBytes(live);
    const y = recordBytes(saved);
    return x.length === y.length && x.every((v, i) => v === y[i]);
  };
  restoreData(core, data, () => restoreStateBytes(J, jolt, (rec) => core.world.system.RestoreState(rec)), same);
}
