// Tests of message framing: every client and server message survives encode → decode unchanged, frames are compact
// msgpack arrays led by their opcode, and socket payload shapes are normalised to bytes.
import { describe, expect, it } from 'vitest';
import { encodeClientMessage, encodeServerMessage, toBytes, unpackFrame } from '../../../shared/protocol/codec.ts';
import { ByeReason, ClientOpcode, ErrorCode, PROTOCOL_VERSION, ServerOpcode } from '../../../shared/protocol/opcodes.ts';
import type { ClientMessage } from '../../../shared/protocol/client-messages.ts';
import type { ServerMessage } from '../../../shared/protocol/server-messages.ts';
import { decodeServerMessage } from '../../../shared/protocol/server-message-decoder.ts';
import { decodeClientMessage } from '../../../shared/protocol/validation.ts';
import { sampleWelcome } from './sample-messages.ts';

describe('codec', () => {
  it('round-trips every client message through the server-side validator', () => {
    const messages: ClientMessage[] = [
      { type: 'hello', version: PROTOCOL_VERSION, name: 'Ada', room: 'lobby-1' },
      { type: 'hello', version: PROTOCOL_VERSION, name: 'Bob', room: null },
      { type: 'hello', version: PROTOCOL_VERSION, name: 'Cy', room: 'arena', seatToken: 's1.arena.AAAAAAAAAAAAAAAAAAAAAA.1.x' },
      { type: 'hello', version: PROTOCOL_VERSION, name: 'Di', room: null, resumeToken: 'abc_DEF-123', seatToken: 'seat.token' },
      { type: 'input', firstTick: 500, commands: [{ moveX: -127, moveZ: 127, yaw: 65535, pitch: -16384, buttons: 15 }, { moveX: 0, moveZ: 3, yaw: 1, pitch: 16384, buttons: 0 }] },
      { type: 'ack', tick: 4_000_000_000 },
      { type: 'ping', clientTimeMs: 12345.678 },
      { type: 'bye' },
    ];
    for (const m of messages) {
      const r = decodeClientMessage(encodeClientMessage(m));
      expect(r).toEqual({ ok: true, message: m, clampedCommands: 0 });
    }
  });

  it('round-trips every server message through the client-side decoder', () => {
    const messages: ServerMessage[] = [
      sampleWelcome,
      { ...sampleWelcome, resumeToken: null, resumeGraceMs: 0, resumed: true },
      { type: 'pong', clientTimeMs: 99.5, serverTick: 77, serverTimeMs: 123456.25, missedInputTicks: 2, roomTicksPerSecond: 43, roomSlow: true },
      { type: 'snapshot', bytes: new Uint8Array([1, 2, 3, 250]), descriptors: [] },
      { type: 'snapshot', bytes: new Uint8Array([9]), descriptors: sampleWelcome.dynamicBodies },
      {
        type: 'events',
        events: [
          { type: 'sensorEnter', tick: 5, sensorId: 2, bodyId: 9, playerId: 1 },
          { type: 'sensorExit', tick: 6, sensorId: 2, bodyId: 9 },
          { type: 'playerJoined', tick: 7, playerId: 4, name: 'Cy', bodyId: 11 },
          { type: 'playerLeft', tick: 8, playerId: 4 },
          { type: 'bodySpawned', tick: 9, bodyId: 12 },
          { type: 'bodyRemoved', tick: 10, bodyId: 12 },
          { type: 'scenario', tick: 11, name: 'doorOpen', value: 1 },
        ],
      },
      { type: 'error', code: ErrorCode.BadInput, message: 'input.commands[0]: moveX must be finite' },
      { type: 'bye', reason: ByeReason.ServerShutdown, message: 'server shutting down' },
      { type: 'bye', reason: ByeReason.RoomMoved, message: 'room arena is hosted by another server', url: 'ws://10.0.0.7:8080/' },
    ];
    for (const m of messages) {
      const r = decodeServerMessage(encodeServerMessage(m));
      expect(r.ok).toBe(true);
      if (r.ok) expect(r.message).toEqual(m);
    }
  });

  it('sends a hello without tokens in version 1\'s four-element shape, and tokens in an options map', () => {
    expect(unpackFrame(encodeClientMessage({ type: 'hello', version: PROTOCOL_VERSION, name: 'Ada', room: null }))).toEqual([ClientOpcode.Hello, PROTOCOL_VERSION, 'Ada', null]);
    expect(unpackFrame(encodeClientMessage({ type: 'hello', version: PROTOCOL_VERSION, name: 'Ada', room: null, resumeToken: 'tok' }))).toEqual([ClientOpcode.Hello, PROTOCOL_VERSION, 'Ada', null, { resumeToken: 'tok' }]);
  });

  it('frames messages as msgpack arrays led by their opcode', () => {
    expect(unpackFrame(encodeClientMessage({ type: 'ack', tick: 9 }))).toEqual([ClientOpcode.SnapshotAck, 9]);
    expect((unpackFrame(encodeServerMessage({ type: 'bye', reason: ByeReason.Kicked, message: 'x' })) as unknown[])[0]).toBe(ServerOpcode.Bye);
  });

  it('keeps the frequent messages small', () => {
    const input = encodeClientMessage({ type: 'input', firstTick: 100000, commands: Array.from({ length: 4 }, () => ({ moveX: 127, moveZ: -127, yaw: 40000, pitch: -2000, buttons: 5 })) });
    // 4 worst-case commands of 11 bytes plus opcode, tick and array headers.
    expect(input.length).toBeLessThanOrEqual(52);
    expect(encodeClientMessage({ type: 'ack', tick: 100000 }).length).toBeLessThanOrEqual(7);
    expect(encodeServerMessage({ type: 'snapshot', bytes: new Uint8Array(10), descriptors: [] }).length).toBeLessThanOrEqual(10 + 5);
  });

  it('normalises socket payloads to bytes and refuses text', () => {
    const a = new Uint8Array([1, 2, 3]);
    expect(toBytes(a)).toBe(a);
    expect(Array.from(toBytes(a.buffer)!)).toEqual([1, 2, 3]);
    expect(Array.from(toBytes(new DataView(a.buffer, 1, 2))!)).toEqual([2, 3]);
    expect(Array.from(toBytes([new Uint8Array([1]), new Uint8Array([2, 3])])!)).toEqual([1, 2, 3]);
    expect(toBytes('text')).toBeNull();
  });
});
