// Tests of the client-side decoder of server frames: malformed data, unknown opcodes, wrong field types, bad
// descriptors and unknown events become error results that name the field, never exceptions.
import { describe, expect, it } from 'vitest';
import { decodeFrame, encodeServerMessage, packValue, unpackFrame } from '../../../shared/protocol/codec.ts';
import { parseShape, unpackDescriptors } from '../../../shared/protocol/descriptor-codec.ts';
import { PROTOCOL_VERSION, ServerOpcode } from '../../../shared/protocol/opcodes.ts';
import { decodeServerMessage } from '../../../shared/protocol/server-message-decoder.ts';
import { Prng } from '../../../shared/sim/prng.ts';
import { frameHex, hostileFrame } from '../../helpers/hostile-frames.ts';
import { sampleWelcome } from './sample-messages.ts';

function errorOf(data: unknown): string {
  const r = decodeServerMessage(data);
  if (r.ok) throw new Error(`expected an error, got ${r.message.type}`);
  return r.error;
}

describe('server-message-decoder', () => {
  it('rejects non-binary, non-msgpack and non-array frames', () => {
    expect(errorOf('hi')).toMatch(/binary/);
    expect(errorOf(new Uint8Array([0x92, 1]))).toMatch(/^not a plain msgpack value: byte 0: a container of 2 values, but only 1 bytes follow/);
    expect(errorOf(packValue({ a: 1 }))).toMatch(/array \[opcode/);
    expect(errorOf(packValue([3]))).toBe('unknown server opcode 3');
  });

  it('names the bad field of a pong, snapshot, error or bye', () => {
    expect(errorOf(packValue([ServerOpcode.Pong, 1, -1, 2, 0, 60, false]))).toMatch(/pong.serverTick/);
    expect(errorOf(packValue([ServerOpcode.Pong, 1, 2, Number.NaN, 0, 60, false]))).toMatch(/pong.serverTimeMs/);
    expect(errorOf(packValue([ServerOpcode.Pong, 1, 2, 3]))).toMatch(/pong must have 6 field/);
    expect(errorOf(packValue([ServerOpcode.Pong, 1, 2, 3, 0, -1, false]))).toMatch(/pong.roomTicksPerSecond/);
    expect(errorOf(packValue([ServerOpcode.Pong, 1, 2, 3, 0, 60, 1]))).toMatch(/pong.roomSlow/);
    expect(errorOf(packValue([ServerOpcode.Snapshot, 'bytes', null]))).toMatch(/snapshot.bytes must be binary/);
    expect(errorOf(packValue([ServerOpcode.Snapshot, new Uint8Array(1), [[], [[1]]]]))).toMatch(/snapshot.descriptors.rows\[0\]/);
    expect(errorOf(packValue([ServerOpcode.Error, 5, 'x']))).toMatch(/error.code/);
    expect(errorOf(packValue([ServerOpcode.Bye, 'kicked']))).toMatch(/bye must have 2 or 3 fields, got 1/);
    expect(errorOf(packValue([ServerOpcode.Bye, 'room-moved', 'elsewhere', 7]))).toMatch(/bye\.url/);
  });

  it('checks every welcome field, including the snapshot format and geometry', () => {
    const welcome = unpackFrame(encodeServerMessage(sampleWelcome)) as [number, Record<string, unknown>];
    const broken = (patch: (w: Record<string, unknown>) => void): string => {
      const copy = structuredClone(welcome);
      patch(copy[1]);
      return errorOf(packValue(copy));
    };
    expect(broken((w) => delete w.playerId)).toMatch(/welcome.playerId/);
    expect(broken((w) => (w.snapshotFormat = { positionSteps: [1, 2] }))).toMatch(/welcome.snapshotFormat/);
    expect(broken((w) => ((w.scenario as { bounds: unknown }).bounds = { min: { x: 0, y: 0 }, max: { x: 1, y: 1, z: 1 } }))).toMatch(/bounds.min.z/);
    expect(broken((w) => ((w.scenario as { params: unknown }).params = { a: 'x' }))).toMatch(/params.a/);
    expect(broken((w) => (w.staticBodies = [[{ kind: 'box' }], []]))).toMatch(/welcome.staticBodies.shapes\[0\].halfExtents/);
  });

  it('checks the welcome\'s resume fields and input delay, and reports a welcome of another version without reading its fields', () => {
    const welcome = unpackFrame(encodeServerMessage(sampleWelcome)) as [number, Record<string, unknown>];
    const patched = (patch: (w: Record<string, unknown>) => void) => {
      const copy = structuredClone(welcome);
      patch(copy[1]);
      return decodeServerMessage(packValue(copy));
    };
    expect(patched((w) => (w.resumeToken = 'has space'))).toMatchObject({ ok: false, error: expect.stringMatching(/welcome.resumeToken must be a token/) });
    expect(patched((w) => delete w.resumed)).toMatchObject({ ok: false, error: 'welcome.resumed must be true or false' });
    expect(patched((w) => (w.resumeGraceMs = -1))).toMatchObject({ ok: false, error: expect.stringMatching(/welcome.resumeGraceMs/) });
    expect(patched((w) => (w.resumeToken = null))).toMatchObject({ ok: true, message: { resumeToken: null } });
    expect(patched((w) => (w.inputDelayTicks = 16))).toMatchObject({ ok: false, error: 'welcome.inputDelayTicks must be at most 15, got 16' });
    expect(patched((w) => delete w.inputDelayTicks)).toMatchObject({ ok: false, error: expect.stringMatching(/welcome.inputDelayTicks must be an integer/) });
    expect(patched((w) => (w.inputDelayTicks = 2))).toMatchObject({ ok: true, message: { inputDelayTicks: 2 } });
    const old = decodeServerMessage(packValue([ServerOpcode.Welcome, { protocolVersion: 1, playerId: 3 }]));
    expect(old).toEqual({ ok: false, error: `the server speaks protocol 1, this client ${PROTOCOL_VERSION}`, serverVersion: 1 });
  });

  it('rejects unknown event types and events with missing fields', () => {
    expect(errorOf(packValue([ServerOpcode.Events, [{ type: 'explode', tick: 1 }]]))).toMatch(/events\[0\].type "explode"/);
    expect(errorOf(packValue([ServerOpcode.Events, [{ type: 'bodySpawned', tick: 1 }]]))).toMatch(/events\[0\].bodyId/);
    expect(errorOf(packValue([ServerOpcode.Events, [{ type: 'playerLeft', tick: -1, playerId: 1 }]]))).toMatch(/events\[0\].tick/);
  });

  it('never throws on random garbage', () => {
    const rng = new Prng(4);
    const valid = encodeServerMessage(sampleWelcome);
    for (let i = 0; i < 3000; i++) {
      const bytes = valid.slice();
      for (let k = 0; k < 3; k++) bytes[rng.int(0, bytes.length - 1)] = rng.int(0, 255);
      const r = decodeServerMessage(bytes);
      if (!r.ok) expect(typeof r.error).toBe('string');
    }
  });

  it('never throws on 20,000 generated hostile frames and answers each with an error sentence', () => {
    const rng = new Prng(0xdec0de);
    const problems: string[] = [];
    for (let i = 0; i < 20_000; i++) {
      const frame = hostileFrame(rng, 100);
      try {
        const r = decodeServerMessage(frame.data);
        if (!r.ok && (typeof r.error !== 'string' || r.error.includes('[object'))) problems.push(`odd error ${String(r.error)} for ${frameHex(frame)}`);
      } catch (error) {
        problems.push(`threw ${(error as Error).message} on ${frameHex(frame)}`);
      }
    }
    expect(problems.slice(0, 5)).toEqual([]);
  });

  it('refuses every decoded hostile value as a shape or descriptor table with an Error naming the field', () => {
    const rng = new Prng(0x5ba9e);
    const problems: string[] = [];
    let tried = 0;
    for (let i = 0; i < 20_000; i++) {
      const frame = hostileFrame(rng, 100);
      if (typeof frame.data === 'string') continue;
      const decoded = decodeFrame(frame.data);
      if (!decoded.ok) continue;
      const v = decoded.value;
      tried++;
      const row = [1, 0, 1, 1, 1, 1, 0, -1, 0, 0, 0, 0, 0, 0, 1];
      for (const parse of [() => parseShape(v), () => unpackDescriptors(v), () => unpackDescriptors([[v], [row]]), () => unpackDescriptors([[{ kind: 'sphere', radius: 1 }], [v]])]) {
        try {
          parse();
        } catch (error) {
          if (!(error instanceof Error) || !error.message.startsWith('descriptor ') || error.message.includes('[object')) problems.push(`${String(error)} for ${frameHex(frame)}`);
        }
      }
    }
    expect(problems.slice(0, 5)).toEqual([]);
    expect(tried).toBeGreaterThan(5000);
  });
});
