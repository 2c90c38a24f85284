// Tests for the input-log payload codecs: exact round trips, compactness, and clear errors on bad records.
import { describe, expect, it } from 'vitest';
import { PayloadError } from '../../../shared/byte-io.ts';
import { decodeCheckpoint, decodeEnd, decodeHash, decodeHeader, decodeTick, encodeCheckpoint, encodeEnd, encodeHash, encodeHeader, encodeTick } from '../../../server/log/record-codec.ts';
import { emptyTickInput } from '../../../shared/sim/types.ts';
import { sampleHeader, sampleTick } from '../../helpers/input-log.ts';

describe('record-codec', () => {
  it('round-trips tick records exactly, including joins with Unicode names, leaves and every command field', () => {
    for (let t = 0; t < 120; t++) {
      const rec = sampleTick(t, 4);
      expect(decodeTick(encodeTick(rec))).toEqual(rec);
    }
    const extremes = {
      tick: 2 ** 40,
      leaves: [0, 0xffffffff],
      joins: [{ playerId: 7, name: '' }],
      commands: [
        { playerId: 1, input: { moveX: -127, moveZ: 127, yaw: 65535, pitch: -16384, buttons: 15 } },
        { playerId: 2, input: { moveX: 0, moveZ: 0, yaw: 0, pitch: 16384, buttons: 0 } },
      ],
    };
    expect(decodeTick(encodeTick(extremes))).toEqual(extremes);
  });

  it('stores an idle tick in 4 bytes and an idle player command in 2', () => {
    expect(encodeTick(emptyTickInput(5)).length).toBe(4);
    const idle = { ...emptyTickInput(5), commands: [{ playerId: 3, input: { moveX: 0, moveZ: 0, yaw: 0, pitch: 0, buttons: 0 } }] };
    expect(encodeTick(idle).length).toBe(6);
  });

  it('rejects records the log cannot store faithfully, naming the problem', () => {
    const cmd = (input: Record<string, unknown>) => ({ ...emptyTickInput(1), commands: [{ playerId: 1, input: { moveX: 0, moveZ: 0, yaw: 0, pitch: 0, buttons: 0, ...input } as never }] });
    expect(() => encodeTick(cmd({ moveX: Number.NaN }))).toThrow(/player 1 is invalid: moveX must be finite/);
    expect(() => encodeTick(cmd({ moveX: 200 }))).toThrow(/not a validated InputCommand/);
    expect(() => encodeTick(cmd({ moveX: 0.5 }))).toThrow(/not a validated InputCommand/);
    expect(() => encodeTick({ ...emptyTickInput(1), leaves: [3, 2] })).toThrow(/sorted ascending and unique \(3 then 2\)/);
    expect(() => encodeTick({ ...emptyTickInput(1), leaves: [-1] })).toThrow(/player id must be an integer/);
    expect(() => encodeTick({ ...emptyTickInput(-1) })).toThrow(/tick must be a non-negative integer/);
    expect(() => encodeTick({ ...emptyTickInput(1), joins: [{ playerId: 1, name: 'x'.repeat(2000) }] })).toThrow(/longer than 1024 bytes/);
  });

  it('rejects decoded commands outside the validator ranges and trailing bytes', () => {
    const bytes = encodeTick({ ...emptyTickInput(0), commands: [{ playerId: 1, input: { moveX: -127, moveZ: 0, yaw: 0, pitch: 0, buttons: 0 } }] });
    const bad = bytes.slice();
    bad[bad.length - 1] = 0x80; // moveX = -128
    expect(() => decodeTick(bad)).toThrow(PayloadError);
    expect(() => decodeTick(Uint8Array.of(...bytes, 0))).toThrow(/trailing/);
    expect(() => decodeTick(bytes.subarray(0, bytes.length - 1))).toThrow(/payload ends inside/);
  });

  it('round-trips headers with numeric and string seeds and sorts parameters', () => {
    const h = { formatVersion: 2, ...sampleHeader({ params: { zeta: 1, alpha: -0.1 }, scenarioHash: `sha256:${'ab'.repeat(32)}` }) };
    const back = decodeHeader(encodeHeader(h), 2);
    expect(back).toEqual(h);
    expect(Object.keys(back.params)).toEqual(['alpha', 'zeta']);
    const s = { formatVersion: 2, ...sampleHeader({ seed: 'night-42' }) };
    expect(decodeHeader(encodeHeader(s), 2).seed).toBe('night-42');
    expect(() => encodeHeader({ ...h, params: { k: Number.POSITIVE_INFINITY } })).toThrow(/parameter k must be a finite number/);
    expect(() => encodeHeader({ ...h, scenario: '' })).toThrow(/scenario name is empty/);
    expect(() => encodeHeader({ ...h, hashEveryTicks: -1 })).toThrow(/hashEveryTicks must be an integer/);
  });

  it('reads a version-1 header, which has no scenario hash, with an empty one', () => {
    const h = { formatVersion: 2, ...sampleHeader({ scenarioHash: '' }) };
    const v2 = encodeHeader(h);
    const v1 = v2.subarray(0, v2.length - 1); // the empty hash is one length byte at the end
    expect(decodeHeader(v1, 1)).toEqual({ ...h, formatVersion: 1 });
    expect(() => decodeHeader(v1, 2)).toThrow(PayloadError);
  });

  it('round-trips hash, checkpoint and end records', () => {
    expect(decodeHash(encodeHash(42, '00ff10a0beefcafe'))).toEqual({ tick: 42, hash: '00ff10a0beefcafe' });
    expect(() => encodeHash(1, 'ABCDEF0123456789')).toThrow(/16 lowercase hex digits/);
    const cp = Uint8Array.from({ length: 5000 }, (_, i) => i & 0xff);
    const back = decodeCheckpoint(encodeCheckpoint(300, cp));
    expect(back.tick).toBe(300);
    expect(back.bytes).toEqual(cp);
    expect(decodeEnd(encodeEnd(7, '0123456789abcdef'))).toEqual({ tick: 7, hash: '0123456789abcdef' });
  });
});
