// Tests of the game-API part of predict-mode records: commands' game input values and a tick's game messages decode
// to exactly the record encoded (a client started mid-stream agrees), they cost a few bits, and hostile bits are
// refused with a clear Error and an unchanged state; whatever a corrupt stream decodes to is a record the simulation
// would accept.
import { describe, expect, it } from 'vitest';
import { BitWriter } from '../../../shared/protocol/bit-stream.ts';
import { RecordDeltaCoder } from '../../../shared/protocol/record-delta.ts';
import type { RecordGameLayout } from '../../../shared/protocol/record-game-bits.ts';
import { resolveGameInputFields } from '../../../shared/sim/game-input.ts';
import { resolveGameMessageKinds, type GameMessage } from '../../../shared/sim/game-messages.ts';
import { NEUTRAL_INPUT, type InputCommand } from '../../../shared/sim/input.ts';
import { Prng } from '../../../shared/sim/prng.ts';
import { validateTickRecord } from '../../../shared/sim/tick-record.ts';
import type { TickInputRecord } from '../../../shared/sim/types.ts';

const LAYOUT: RecordGameLayout = {
  fields: resolveGameInputFields({ push: { kind: 'axis', min: -100, max: 100 }, lift: { kind: 'button' } }, 'test'),
  kinds: resolveGameMessageKinds({ pickTeam: { payload: { team: { min: 0, max: 1 } } }, ready: {}, buy: { payload: { item: { min: -5, max: 500 }, count: { min: 1, max: 9 } } } }, 'test'),
};

/** A seeded session: players join and leave, hold and change game input, and send messages of every kind. */
function gameSession(seed: number, ticks: number): TickInputRecord[] {
  const rng = new Prng(seed);
  const present = new Set<number>();
  const out: TickInputRecord[] = [];
  let nextId = 1;
  for (let tick = 0; tick < ticks; tick++) {
    const leaves = [...present].filter(() => present.size > 2 && rng.next() < 0.01).sort((a, b) => a - b);
    for (const id of leaves) present.delete(id);
    const joins = rng.next() < 0.08 || present.size === 0 ? [{ playerId: nextId++, name: `p${nextId}` }] : [];
    const commands = [...present].sort((a, b) => a - b).filter(() => rng.next() < 0.7).map((playerId) => {
      const input: InputCommand = { moveX: rng.int(-127, 127), moveZ: 0, yaw: rng.int(0, 65535), pitch: 0, buttons: 0, game: [rng.next() < 0.3 ? 1 : 0, rng.next() < 0.5 ? 0 : rng.int(-100, 100)] };
      return { playerId, input };
    });
    const messages: GameMessage[] = [];
    for (const id of [...present, ...joins.map((j) => j.playerId)].sort((a, b) => a - b)) {
      const n = rng.next() < 0.1 ? rng.int(1, 8) : 0;
      for (let i = 0; i < n; i++) {
        const k = rng.int(0, 2);
        const name = LAYOUT.kinds[k].name;
        const payload = LAYOUT.kinds[k].fields.map((f) => rng.int(f.min, f.max));
        messages.push({ playerId: id, name, payload });
      }
    }
    for (const j of joins) present.add(j.playerId);
    out.push(messages.length > 0 ? { tick, leaves, joins, commands, messages } : { tick, leaves, joins, commands });
  }
  return out;
}

/** Every present player's command spelled out, with game values as the records carry them. */
function explicit(records: readonly TickInputRecord[]): TickInputRecord[] {
  const last = new Map<number, InputCommand>();
  return records.map((r) => {
    for (const id of r.leaves) last.delete(id);
    for (const j of r.joins) last.set(j.playerId, { ...NEUTRAL_INPUT, game: [0, 0] });
    for (const c of r.commands) last.set(c.playerId, c.input);
    const commands = [...last.entries()].sort((a, b) => a[0] - b[0]).map(([playerId, input]) => ({ playerId, input }));
    return { ...r, commands };
  });
}

/** Bits of a record for a coder whose only player is 7: no leaves, then `body`. */
function crafted(body: (w: BitWriter) => void): Uint8Array {
  const w = new BitWriter(16);
  w.writeExpGolomb(0, 0);
  body(w);
  return w.finish();
}

const ONE_PLAYER = [{ playerId: 7, input: { ...NEUTRAL_INPUT, game: [0, 0] }, yawStep: 0 }];

describe('record-game-bits', () => {
  it('decodes game input values and game messages to exactly the record encoded, also from a mid-session state', () => {
    const records = gameSession(3, 600);
    const expected = explicit(records);
    expect(records.filter((r) => r.messages).length).toBeGreaterThan(100);
    const server = new RecordDeltaCoder([], LAYOUT);
    const client = new RecordDeltaCoder([], LAYOUT);
    let late: RecordDeltaCoder | null = null;
    for (const r of records) {
      if (r.tick === 300) late = new RecordDeltaCoder(server.state(), LAYOUT);
      const { bits, joins } = server.encode(r);
      expect(client.decode(r.tick, bits, joins)).toEqual(expected[r.tick]);
      if (late) expect(late.decode(r.tick, bits, joins)).toEqual(expected[r.tick]);
    }
    expect(client.state()).toEqual(server.state());
  });

  it('codes a held game input in one bit per player and a message in a few bits', () => {
    const server = new RecordDeltaCoder([], LAYOUT);
    server.encode({ tick: 0, leaves: [], joins: [1, 2, 3, 4].map((playerId) => ({ playerId, name: `p${playerId}` })), commands: [] });
    const held = [1, 2, 3, 4].map((playerId) => ({ playerId, input: { ...NEUTRAL_INPUT, game: [1, -40] } }));
    server.encode({ tick: 1, leaves: [], joins: [], commands: held });
    // 4 players holding their command: one bit each, plus one bit for "no messages".
    expect(server.encode({ tick: 2, leaves: [], joins: [], commands: held }).bits.length).toBe(1);
    const withMessage = server.encode({ tick: 3, leaves: [], joins: [], commands: held, messages: [{ playerId: 3, name: 'pickTeam', payload: [1] }] });
    expect(withMessage.bits.length).toBeLessThanOrEqual(2);
  });

  it('refuses hostile bits with a clear Error and keeps its state', () => {
    const cases: Array<[string, (w: BitWriter) => void, RegExp]> = [
      ['a game value outside its range', (w) => { w.writeBool(true); w.writeBits(32, 6); w.writeBool(false); w.writeBool(true); w.writeSignedExpGolomb(101, 0); w.writeExpGolomb(0, 0); }, /game input push is 101, outside \[-100, 100\]/],
      ['a game field marked changed without a change', (w) => { w.writeBool(true); w.writeBits(32, 6); w.writeBool(true); w.writeSignedExpGolomb(0, 0); }, /lift marked changed without a change/],
      ['game input marked changed with no field', (w) => { w.writeBool(true); w.writeBits(32, 6); w.writeBool(false); w.writeBool(false); }, /marked changed with no field/],
      ['more messages than players may send', (w) => { w.writeBool(false); w.writeExpGolomb(9, 0); }, /9 game messages from 1 players/],
      ['a message naming no player in the game', (w) => { w.writeBool(false); w.writeExpGolomb(1, 0); w.writeExpGolomb(1, 0); }, /names no player in the game/],
      ['an undeclared message kind', (w) => { w.writeBool(false); w.writeExpGolomb(1, 0); w.writeExpGolomb(0, 0); w.writeBits(3, 2); }, /has kind 3, but 3 are declared/],
      ['a payload value outside its range', (w) => { w.writeBool(false); w.writeExpGolomb(1, 0); w.writeExpGolomb(0, 0); w.writeBits(1, 2); w.writeExpGolomb(2, 0); }, /pickTeam: team is 2, outside \[0, 1\]/],
      ['a truncated payload', (w) => { w.writeBool(false); w.writeExpGolomb(1, 0); w.writeExpGolomb(0, 0); w.writeBits(0, 2); }, /truncated|past the end/],
    ];
    for (const [what, body, error] of cases) {
      const client = new RecordDeltaCoder(ONE_PLAYER, LAYOUT);
      const before = client.state();
      expect(() => client.decode(5, crafted(body), []), what).toThrow(error);
      expect(client.state(), what).toEqual(before);
    }
    // The same message, well formed, decodes.
    const ok = new RecordDeltaCoder(ONE_PLAYER, LAYOUT).decode(5, crafted((w) => { w.writeBool(false); w.writeExpGolomb(1, 0); w.writeExpGolomb(0, 0); w.writeBits(1, 2); w.writeExpGolomb(1, 0); }), []);
    expect(ok.messages).toEqual([{ playerId: 7, name: 'pickTeam', payload: [1] }]);
  });

  it('decodes corrupt streams only to records the simulation accepts, else throws an Error', () => {
    const records = gameSession(8, 200);
    const server = new RecordDeltaCoder([], LAYOUT);
    const encoded = records.map((r) => server.encode(r));
    const rng = new Prng(21);
    let refused = 0;
    let accepted = 0;
    for (let trial = 0; trial < 400; trial++) {
      const at = rng.int(50, 199);
      const replay = new RecordDeltaCoder([], LAYOUT);
      for (let t = 0; t < at; t++) replay.decode(t, encoded[t].bits, encoded[t].joins);
      const present = new Set(replay.state().map((p) => p.playerId));
      const bits = encoded[at].bits.slice();
      const flips = rng.int(1, 3);
      for (let i = 0; i < flips; i++) bits[rng.int(0, bits.length - 1)] ^= 1 << rng.int(0, 7);
      const before = replay.state();
      try {
        const record = replay.decode(at, bits, encoded[at].joins);
        expect(() => validateTickRecord(record, at, (id) => present.has(id), LAYOUT.fields, LAYOUT.kinds)).not.toThrow();
        accepted++;
      } catch (error) {
        expect(error).toBeInstanceOf(Error);
        expect((error as Error).message).toMatch(/record of tick|bit stream/);
        expect(replay.state()).toEqual(before);
        refused++;
      }
    }
    expect(refused).toBeGreaterThan(100);
    expect(accepted + refused).toBe(400);
  });

  it('refuses a starting state whose game values do not fit the scenario, and messages for a scenario without kinds', () => {
    expect(() => new RecordDeltaCoder([{ playerId: 1, input: { ...NEUTRAL_INPUT, game: [2, 0] }, yawStep: 0 }], LAYOUT)).toThrow(/player 1's game input \(2 values\) does not fit the scenario's fields lift \[0, 1\], push \[-100, 100\]/);
    expect(() => new RecordDeltaCoder([{ playerId: 1, input: { ...NEUTRAL_INPUT, game: [1] }, yawStep: 0 }], LAYOUT)).toThrow(/\(1 values\) does not fit/);
    const plain = new RecordDeltaCoder();
    expect(() => plain.encode({ tick: 0, leaves: [], joins: [{ playerId: 1, name: 'a' }], commands: [], messages: [{ playerId: 1, name: 'ready', payload: [] }] })).toThrow(/game messages but the scenario declares none/);
  });
});
