// Tests of predict mode's messages on the wire: resync and netMode requests are validated like any hostile client
// frame, and checkpoint and record messages round-trip through the codec and are refused when malformed.
import { describe, expect, it } from 'vitest';
import { encodeClientMessage, encodeServerMessage, packValue } from '../../../shared/protocol/codec.ts';
import { ClientOpcode, ErrorCode, ServerOpcode } from '../../../shared/protocol/opcodes.ts';
import { carriesHash, type CheckpointMessage, type RecordMessage } from '../../../shared/protocol/predict-messages.ts';
import { decodeServerMessage } from '../../../shared/protocol/server-message-decoder.ts';
import { decodeClientMessage } from '../../../shared/protocol/validation.ts';

describe('predict-messages', () => {
  it('accepts resync and netMode requests and refuses any other shape', () => {
    expect(decodeClientMessage(encodeClientMessage({ type: 'resync' }))).toEqual({ ok: true, message: { type: 'resync' }, clampedCommands: 0 });
    expect(decodeClientMessage(encodeClientMessage({ type: 'netMode', mode: 'snapshot' }))).toEqual({ ok: true, message: { type: 'netMode', mode: 'snapshot' }, clampedCommands: 0 });
    for (const bad of [[ClientOpcode.Resync, 1], [ClientOpcode.NetMode], [ClientOpcode.NetMode, 'lockstep'], [ClientOpcode.NetMode, 1], [ClientOpcode.NetMode, 'predict', 0]]) {
      const r = decodeClientMessage(packValue(bad));
      expect(r.ok, JSON.stringify(bad)).toBe(false);
      if (!r.ok) expect(r.code).toBe(ErrorCode.BadMessage);
    }
  });

  it('round-trips checkpoints and records, with joins and the hash only when present', () => {
    const checkpoint: CheckpointMessage = { type: 'checkpoint', tick: 1234, seed: 'seed-7', bytes: Uint8Array.of(1, 2, 3), inputs: [{ playerId: 4, input: { moveX: -3, moveZ: 127, yaw: 65535, pitch: -16384, buttons: 5 }, yawStep: -250 }] };
    expect(decodeServerMessage(encodeServerMessage(checkpoint))).toEqual({ ok: true, message: checkpoint });
    // A game-API scenario's player also carries its game input values.
    const withGame: CheckpointMessage = { ...checkpoint, inputs: [{ ...checkpoint.inputs[0], input: { ...checkpoint.inputs[0].input, game: [1, -40] } }] };
    expect(decodeServerMessage(encodeServerMessage(withGame))).toEqual({ ok: true, message: withGame });
    const plain: RecordMessage = { type: 'record', tickLow: 17, bits: Uint8Array.of(9), joins: [], hash: null };
    expect(encodeServerMessage(plain).length).toBeLessThanOrEqual(6);
    expect(decodeServerMessage(encodeServerMessage(plain))).toEqual({ ok: true, message: plain });
    const full: RecordMessage = { type: 'record', tickLow: 255, bits: Uint8Array.of(9, 8), joins: [{ playerId: 2, name: 'Ada' }], hash: '0123456789abcdef' };
    expect(decodeServerMessage(encodeServerMessage(full))).toEqual({ ok: true, message: full });
    const hashOnly: RecordMessage = { ...plain, hash: 'ffffffff00000000' };
    expect(decodeServerMessage(encodeServerMessage(hashOnly))).toEqual({ ok: true, message: hashOnly });
    expect(carriesHash(29)).toBe(true);
    expect(carriesHash(30)).toBe(false);
  });

  it('refuses malformed checkpoints and records with a reason', () => {
    const bad: unknown[][] = [
      [ServerOpcode.Record, 256, Uint8Array.of(0)],
      [ServerOpcode.Record, 1, 'bits'],
      [ServerOpcode.Record, 1, Uint8Array.of(0), [[1]]],
      [ServerOpcode.Record, 1, Uint8Array.of(0), null, Uint8Array.of(1, 2)],
      [ServerOpcode.Record, 1, Uint8Array.of(0), null, Uint8Array.of(1, 2, 3, 4, 5, 6, 7, 8), 0],
      [ServerOpcode.Checkpoint, 1, 1.5, Uint8Array.of(0), []],
      [ServerOpcode.Checkpoint, 1, 1, Uint8Array.of(0), [[1, 0, 0, 0, 0, 0]]],
      [ServerOpcode.Checkpoint, 1, 1, Uint8Array.of(0), [[1, 200, 0, 0, 0, 0, 0]]],
      [ServerOpcode.Checkpoint, -1, 1, Uint8Array.of(0), []],
      [ServerOpcode.Checkpoint, 1, 1, Uint8Array.of(0), [[1, 0, 0, 0, 0, 0, 0, []]]],
      [ServerOpcode.Checkpoint, 1, 1, Uint8Array.of(0), [[1, 0, 0, 0, 0, 0, 0, 5]]],
      [ServerOpcode.Checkpoint, 1, 1, Uint8Array.of(0), [[1, 0, 0, 0, 0, 0, 0, [0.5]]]],
      [ServerOpcode.Checkpoint, 1, 1, Uint8Array.of(0), [[1, 0, 0, 0, 0, 0, 0, [2_000_000]]]],
      [ServerOpcode.Checkpoint, 1, 1, Uint8Array.of(0), [[1, 0, 0, 0, 0, 0, 0, new Array(17).fill(0)]]],
      [ServerOpcode.Checkpoint, 1, 1, Uint8Array.of(0), [[1, 0, 0, 0, 0, 0, 0, [0], 9]]],
    ];
    for (const value of bad) {
      const r = decodeServerMessage(packValue(value));
      expect(r.ok, JSON.stringify(value, (_k, v: unknown) => (v instanceof Uint8Array ? [...v] : v))).toBe(false);
    }
  });
});
