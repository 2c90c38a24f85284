// Tests of the predict-mode record coder: records of a busy bot session (joins, leaves, turning, firing) decode to
// exactly what was encoded, a decoder started from a mid-stream state agrees, bots cost a few bits per player, and
// corrupt bits are refused with an Error that leaves the state unchanged.
import { describe, expect, it } from 'vitest';
import { RecordDeltaCoder } from '../../../shared/protocol/record-delta.ts';
import { BotScript } from '../../../shared/sim/bots.ts';
import { NEUTRAL_INPUT, type InputCommand } from '../../../shared/sim/input.ts';
import type { TickInputRecord } from '../../../shared/sim/types.ts';

/** The record with every present player's command spelled out (an absent command repeats the player's last). */
function explicit(records: readonly TickInputRecord[]): TickInputRecord[] {
  const last = new Map<number, InputCommand>();
  return records.map((r) => {
    for (const id of r.leaves) last.delete(id);
    for (const j of r.joins) last.set(j.playerId, { ...NEUTRAL_INPUT });
    for (const c of r.commands) last.set(c.playerId, c.input);
    const commands = [...last.entries()].sort((a, b) => a[0] - b[0]).map(([playerId, input]) => ({ playerId, input }));
    return { ...r, commands };
  });
}

function session(ticks: number): TickInputRecord[] {
  return new BotScript({ seed: 4, bots: 5, joinTicks: [0, 3, 10, 40, 41], leaveTicks: [-1, 90, -1, 200, -1] }).take(ticks);
}

describe('record-delta', () => {
  it('decodes every record of a busy session to exactly the record encoded', () => {
    const records = session(300);
    const expected = explicit(records);
    const server = new RecordDeltaCoder();
    const client = new RecordDeltaCoder();
    for (const r of records) {
      const { bits, joins } = server.encode(r);
      expect(client.decode(r.tick, bits, joins)).toEqual(expected[r.tick]);
    }
    // Sparse records (a player without a command) code the same as the room's, where every player has one.
    const sparseCoder = new RecordDeltaCoder();
    const denseCoder = new RecordDeltaCoder();
    // Player 3 holds one command from its join on: given only on its join tick, or every tick, it codes the same.
    const held = { moveX: 5, moveZ: -7, yaw: 100, pitch: 3, buttons: 4 };
    let omitted = 0;
    for (const r of expected) {
      const dense = r.commands.map((c) => (c.playerId === 3 ? { playerId: 3, input: held } : c));
      const joining = r.joins.some((j) => j.playerId === 3);
      const sparse = dense.filter((c) => c.playerId !== 3 || joining);
      omitted += dense.length - sparse.length;
      expect(sparseCoder.encode({ ...r, commands: sparse }).bits).toEqual(denseCoder.encode({ ...r, commands: dense }).bits);
    }
    expect(omitted).toBeGreaterThan(100);
    expect(client.state()).toEqual(server.state());
  });

  it('lets a client start from a mid-session state (a checkpoint) and agree from there', () => {
    const records = session(200);
    const expected = explicit(records);
    const server = new RecordDeltaCoder();
    for (const r of records.slice(0, 120)) server.encode(r);
    const late = new RecordDeltaCoder(server.state());
    for (const r of records.slice(120)) {
      const { bits, joins } = server.encode(r);
      expect(late.decode(r.tick, bits, joins)).toEqual(expected[r.tick]);
    }
  });

  it('spends under 2 bytes per turning, walking, firing bot per tick', () => {
    const records = new BotScript({ seed: 9, bots: 4, joinSpacingTicks: 0 }).take(600);
    const server = new RecordDeltaCoder();
    let bytes = 0;
    for (const r of records) bytes += server.encode(r).bits.length;
    expect(bytes / (600 * 4)).toBeLessThan(2);
  });

  it('refuses corrupt bits with an Error and keeps its state', () => {
    const records = session(60);
    const server = new RecordDeltaCoder();
    const client = new RecordDeltaCoder();
    for (const r of records.slice(0, 59)) {
      const e = server.encode(r);
      client.decode(r.tick, e.bits, e.joins);
    }
    const before = client.state();
    const next = server.encode(records[59]);
    let refused = 0;
    for (let seed = 1; seed <= 400; seed++) {
      const bits = next.bits.slice();
      bits[seed % bits.length] ^= 1 + (seed % 255);
      const extra = seed % 3 === 0 ? Uint8Array.of(...bits, 0xff) : bits;
      try {
        const copy = new RecordDeltaCoder(before);
        copy.decode(59, extra, []);
      } catch (error) {
        expect(error).toBeInstanceOf(Error);
        refused++;
      }
    }
    expect(refused).toBeGreaterThan(0);
    expect(() => client.decode(59, new Uint8Array(0), [])).toThrow(/truncated/);
    expect(client.state()).toEqual(before);
    expect(() => client.decode(59, next.bits, [{ playerId: 1, name: 'again' }])).toThrow(/already in the game/);
    expect(client.state()).toEqual(before);
    expect(client.decode(59, next.bits, next.joins)).toEqual(explicit(records)[59]);
  });

  it('refuses to encode a command for a player who is not in the game', () => {
    const server = new RecordDeltaCoder();
    server.encode({ tick: 0, leaves: [], joins: [{ playerId: 3, name: 'a' }], commands: [] });
    expect(() => server.encode({ tick: 1, leaves: [3], joins: [], commands: [{ playerId: 3, input: { ...NEUTRAL_INPUT } }] })).toThrow(/command for player 3, who is not in the game/);
  });

  it('advances past records without bits to exactly where encoding them would have left it', () => {
    const records = explicit(session(300));
    const encoding = new RecordDeltaCoder();
    const skipping = new RecordDeltaCoder();
    for (const r of records) {
      const encoded = encoding.encode(r);
      // A room skips while no member takes records, then a member starts predicting and it encodes again.
      if (r.tick < 150 || (r.tick >= 200 && r.tick < 250)) skipping.advance(r);
      else expect(skipping.encode(r)).toEqual(encoded);
      expect(skipping.state()).toEqual(encoding.state());
    }
  });

  it('refuses a command for a player who is not in the game before changing any state', () => {
    const server = new RecordDeltaCoder();
    server.encode({ tick: 0, leaves: [], joins: [{ playerId: 2, name: 'a' }, { playerId: 5, name: 'b' }], commands: [] });
    const before = server.state();
    const walk = { ...NEUTRAL_INPUT, moveX: 40 };
    expect(() => server.encode({ tick: 1, leaves: [], joins: [], commands: [{ playerId: 2, input: walk }, { playerId: 4, input: walk }] })).toThrow(/command for player 4, who is not in the game/);
    expect(() => server.advance({ tick: 1, leaves: [], joins: [], commands: [{ playerId: 6, input: walk }, { playerId: 2, input: walk }] })).toThrow(/command for player 6, who is not in the game/);
    expect(server.state()).toEqual(before);
  });
});
