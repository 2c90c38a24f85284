// Framing with msgpackr: every message is one msgpack array [opcode, …fields] in one binary WebSocket frame.
// Encoders for both directions live here; decoding is checked in validation.ts (client→server) and
// server-message-decoder.ts (server→client).
import { Packr, Unpackr } from 'msgpackr';
import type { SimEvent } from '../sim/types.ts';
import type { ClientMessage } from './client-messages.ts';
import { packDescriptors } from './descriptor-codec.ts';
import { packGameSchema } from './game-schema-codec.ts';
import { scanMsgpack } from './msgpack-scan.ts';
import { ClientOpcode, ServerOpcode } from './opcodes.ts';
import type { ServerMessage } from './server-messages.ts';

// Plain msgpack: no record extension, no typed-array extensions, maps decode to plain objects. 64-bit integers
// decode as numbers (never bigints); scanMsgpack has already refused every extension type before unpackr runs.
const packr = new Packr({ useRecords: false, moreTypes: false });
const unpackr = new Unpackr({ useRecords: false, moreTypes: false, mapsAsObjects: true, int64AsType: 'number' });

/** Nesting limit of frames the server sends (welcome geometry with compound shapes is the deepest). */
export const MAX_SERVER_FRAME_DEPTH = 64;

/** Turns what a socket delivers (Uint8Array, ArrayBuffer, a view, or ws's Buffer[] fragments) into bytes; null if not binary. */
export function toBytes(data: unknown): Uint8Array | null {
  if (data instanceof Uint8Array) return data;
  if (data instanceof ArrayBuffer) return new Uint8Array(data);
  if (ArrayBuffer.isView(data)) return new Uint8Array(data.buffer, data.byteOffset, data.byteLength);
  if (Array.isArray(data) && data.every((d) => d instanceof Uint8Array)) {
    const total = data.reduce((n: number, d: Uint8Array) => n + d.length, 0);
    const out = new Uint8Array(total);
    let o = 0;
    for (const d of data as Uint8Array[]) {
      out.set(d, o);
      o += d.length;
    }
    return out;
  }
  return null;
}

/** A frame that is not one plain msgpack value (see scanMsgpack). */
export class FrameError extends Error {
  override name = 'FrameError';
}

/** One decoded frame, or why it is not one plain msgpack value. */
export type FrameDecode = { ok: true; value: unknown } | { ok: false; error: string };

/**
 * Decodes one msgpack value that must span the whole buffer, after scanMsgpack has checked its structure (plain
 * types only, at most `maxDepth` nested containers). Never throws: a refusal costs no exception (no stack trace),
 * which keeps garbage cheap to turn away. A decoded value holds only null, booleans, numbers, strings,
 * Uint8Arrays, arrays and plain objects whose keys are strings.
 */
export function decodeFrame(bytes: Uint8Array, maxDepth: number = MAX_SERVER_FRAME_DEPTH): FrameDecode {
  const problem = scanMsgpack(bytes, maxDepth);
  if (problem !== null) return { ok: false, error: problem };
  try {
    return { ok: true, value: unpackr.unpack(bytes) };
  } catch (error) {
    return { ok: false, error: error instanceof Error ? error.message.slice(0, 120) : 'msgpack decoding failed' };
  }
}

/** decodeFrame for callers that want the value or an exception (FrameError). */
export function unpackFrame(bytes: Uint8Array, maxDepth: number = MAX_SERVER_FRAME_DEPTH): unknown {
  const r = decodeFrame(bytes, maxDepth);
  if (!r.ok) throw new FrameError(r.error);
  return r.value;
}

/** Encodes any plain value as msgpack (tests and tools; messages go through the typed encoders). */
export function packValue(value: unknown): Uint8Array {
  return packr.pack(value);
}

/** Encodes a client→server message. */
export function encodeClientMessage(m: ClientMessage): Uint8Array {
  switch (m.type) {
    case 'hello': {
      // The options map is sent only when there is an option, so a hello without tokens keeps version 1's shape
      // and an older server can still answer it with version-mismatch.
      const options: { seatToken?: string; resumeToken?: string } = {};
      if (m.seatToken !== undefined) options.seatToken = m.seatToken;
      if (m.resumeToken !== undefined) options.resumeToken = m.resumeToken;
      const base = [ClientOpcode.Hello, m.version, m.name, m.room];
      return packr.pack(m.seatToken !== undefined || m.resumeToken !== undefined ? [...base, options] : base);
    }
    case 'input': {
      const commands = m.commands.map((c) => (c.game !== undefined && c.game.length > 0 ? [c.moveX, c.moveZ, c.yaw, c.pitch, c.buttons, [...c.game]] : [c.moveX, c.moveZ, c.yaw, c.pitch, c.buttons]));
      return packr.pack(m.ackTick === undefined ? [ClientOpcode.Input, m.firstTick, commands] : [ClientOpcode.Input, m.firstTick, commands, m.ackTick]);
    }
    case 'ack':
      return packr.pack([ClientOpcode.SnapshotAck, m.tick]);
    case 'ping':
      return packr.pack([ClientOpcode.Ping, m.clientTimeMs]);
    case 'bye':
      return packr.pack([ClientOpcode.Bye]);
    case 'resync':
      return packr.pack([ClientOpcode.Resync]);
    case 'netMode':
      return packr.pack([ClientOpcode.NetMode, m.mode]);
    case 'game':
      return packr.pack(m.tick === undefined ? [ClientOpcode.GameMessage, m.name, [...m.payload]] : [ClientOpcode.GameMessage, m.name, [...m.payload], m.tick]);
  }
}

/** A copy of an event without undefined fields (msgpack has no undefined). */
function plainEvent(e: SimEvent): Record<string, unknown> {
  const out: Record<string, unknown> = {};
  for (const [k, v] of Object.entries(e)) if (v !== undefined) out[k] = v;
  return out;
}

/** A 16-hex state hash as its 8 bytes. */
export function hashBytes(hash: string): Uint8Array {
  if (!/^[0-9a-f]{16}$/.test(hash)) throw new Error(`a state hash must be 16 lowercase hex characters, got ${hash}`);
  const out = new Uint8Array(8);
  for (let i = 0; i < 8; i++) out[i] = parseInt(hash.slice(2 * i, 2 * i + 2), 16);
  return out;
}

/** Encodes a server→client message. */
export function encodeServerMessage(m: ServerMessage): Uint8Array {
  switch (m.type) {
    case 'welcome':
      return packr.pack([
        ServerOpcode.Welcome,
        {
          protocolVersion: m.protocolVersion,
          playerId: m.playerId,
          roomId: m.roomId,
          tick: m.tick,
          tickRateHz: m.tickRateHz,
          snapshotRateHz: m.snapshotRateHz,
          scenario: {
            name: m.scenario.name,
            description: m.scenario.description,
            params: { ...m.scenario.params },
            bounds: {
              min: { x: m.scenario.bounds.min.x, y: m.scenario.bounds.min.y, z: m.scenario.bounds.min.z },
              max: { x: m.scenario.bounds.max.x, y: m.scenario.bounds.max.y, z: m.scenario.bounds.max.z },
            },
            ...packGameSchema(m.scenario.game ?? {}),
          },
          snapshotFormat: { positionSteps: [...m.snapshotFormat.positionSteps], rotationBits: m.snapshotFormat.rotationBits },
          staticBodies: packDescriptors(m.staticBodies),
          dynamicBodies: packDescriptors(m.dynamicBodies),
          resumeToken: m.resumeToken,
          resumeGraceMs: m.resumeGraceMs,
          resumed: m.resumed,
          netMode: m.netMode,
          inputDelayTicks: m.inputDelayTicks,
        },
      ]);
    case 'pong':
      return packr.pack([ServerOpcode.Pong, m.clientTimeMs, m.serverTick, m.serverTimeMs, m.missedInputTicks, m.roomTicksPerSecond, m.roomSlow]);
    case 'snapshot':
      // Without descriptors or game state, a snapshot is its opcode byte and the snapshot bytes: not msgpack (a
      // msgpack frame starts with an array header), which saves the array, bin and null headers on the hot path.
      if (m.descriptors.length === 0 && m.state === undefined) {
        const out = new Uint8Array(1 + m.bytes.length);
        out[0] = ServerOpcode.Snapshot;
        out.set(m.bytes, 1);
        return out;
      }
      if (m.state !== undefined) return packr.pack([ServerOpcode.Snapshot, m.bytes, m.descriptors.length > 0 ? packDescriptors(m.descriptors) : null, m.state]);
      return packr.pack([ServerOpcode.Snapshot, m.bytes, m.descriptors.length > 0 ? packDescriptors(m.descriptors) : null]);
    case 'events':
      return packr.pack([ServerOpcode.Events, m.events.map(plainEvent)]);
    case 'error':
      return packr.pack([ServerOpcode.Error, m.code, m.message]);
    case 'bye':
      return packr.pack(m.url === undefined ? [ServerOpcode.Bye, m.reason, m.message] : [ServerOpcode.Bye, m.reason, m.message, m.url]);
    case 'checkpoint':
      return packr.pack([ServerOpcode.Checkpoint, m.tick, m.seed, m.bytes, m.inputs.map((p) => { const row: unknown[] = [p.playerId, p.input.moveX, p.input.moveZ, p.input.yaw, p.input.pitch, p.input.buttons, p.yawStep]; if ((p.input.game?.length ?? 0) > 0) row.push([...p.input.game!]); return row; })]);
    case 'record': {
      // Joins and the hash only when present: most records are [23, tickLow, bits].
      const fields: unknown[] = [ServerOpcode.Record, m.tickLow, m.bits];
      if (m.joins.length > 0 || m.hash !== null) fields.push(m.joins.length > 0 ? m.joins.map((j) => [j.playerId, j.name]) : null);
      if (m.hash !== null) fields.push(hashBytes(m.hash));
      return packr.pack(fields);
    }
  }
}
