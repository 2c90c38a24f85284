// Record framing of the input log: type byte, payload length (LEB128, ≤ 4 bytes), a header check byte, the payload,
// and a CRC-32. Encodes frames and classifies the bytes at an offset as a whole frame, "need more", or corrupt.
import { ByteWriter } from '../../shared/byte-io.ts';
import { crc32 } from './crc32.ts';
import { MAX_FRAME_OVERHEAD_BYTES, MAX_LENGTH_VARINT_BYTES, MAX_PAYLOAD_BYTES, RECORD_TYPE_NAMES, type RecordTypeCode } from './log-format.ts';

/** What sits at an offset: a whole valid frame, too few bytes to tell, or a damaged frame. */
export type FrameScan =
  | { kind: 'frame'; type: RecordTypeCode; payloadStart: number; payloadEnd: number; frameEnd: number }
  | { kind: 'need'; totalBytes: number }
  | { kind: 'bad'; reason: string };

/**
 * Appends a frame to `out`: type, length, header check, payload (`payload` then `tail`, if given), CRC-32 (LE) over
 * everything before it. Throws (writing nothing) if the payload exceeds the type's limit.
 */
export function writeFrame(out: ByteWriter, type: RecordTypeCode, payload: Uint8Array, tail?: Uint8Array): void {
  const length = payload.length + (tail?.length ?? 0);
  const max = MAX_PAYLOAD_BYTES[type];
  if (length > max) throw new Error(`${RECORD_TYPE_NAMES[type]} record of ${length} bytes exceeds the ${max}-byte limit`);
  const start = out.length;
  out.u8(type);
  out.uvarint(length);
  out.u8(crc32(out.view(), start, out.length) & 0xff);
  out.raw(payload);
  if (tail) out.raw(tail);
  out.u32(crc32(out.view(), start, out.length));
}

/** A frame as a fresh byte array (see writeFrame). */
export function encodeFrame(type: RecordTypeCode, payload: Uint8Array): Uint8Array {
  const out = new ByteWriter(payload.length + MAX_FRAME_OVERHEAD_BYTES);
  writeFrame(out, type, payload);
  return out.finish();
}

/**
 * Classifies bytes[offset, end) as the start of a frame. `need` means the bytes end inside the frame (at the end
 * of a file: a truncated tail); `bad` names what is damaged (unknown type, header check, length, CRC).
 */
export function scanFrame(bytes: Uint8Array, offset: number, end: number): FrameScan {
  if (end - offset < 1) return { kind: 'need', totalBytes: 1 };
  const type = bytes[offset];
  if (RECORD_TYPE_NAMES[type] === undefined) return { kind: 'bad', reason: `unknown record type 0x${type.toString(16).padStart(2, '0')}` };
  let length = 0;
  let i = 0;
  for (;;) {
    if (i === MAX_LENGTH_VARINT_BYTES) return { kind: 'bad', reason: `bad length: varint longer than ${MAX_LENGTH_VARINT_BYTES} bytes` };
    const at = offset + 1 + i;
    if (at >= end) return { kind: 'need', totalBytes: 2 + i };
    const b = bytes[at];
    length += (b & 0x7f) * (1 << (7 * i));
    i++;
    if ((b & 0x80) === 0) break;
  }
  const headerEnd = offset + 1 + i;
  if (headerEnd >= end) return { kind: 'need', totalBytes: headerEnd + 1 - offset };
  if ((crc32(bytes, offset, headerEnd) & 0xff) !== bytes[headerEnd]) {
    return { kind: 'bad', reason: 'bad length or type: record header check failed' };
  }
  const name = RECORD_TYPE_NAMES[type];
  if (length > MAX_PAYLOAD_BYTES[type]) return { kind: 'bad', reason: `bad length: ${name} record claims ${length} bytes (limit ${MAX_PAYLOAD_BYTES[type]})` };
  const payloadStart = headerEnd + 1;
  const payloadEnd = payloadStart + length;
  const frameEnd = payloadEnd + 4;
  if (frameEnd > end) return { kind: 'need', totalBytes: frameEnd - offset };
  const stored = (bytes[payloadEnd] | (bytes[payloadEnd + 1] << 8) | (bytes[payloadEnd + 2] << 16) | (bytes[payloadEnd + 3] << 24)) >>> 0;
  const computed = crc32(bytes, offset, payloadEnd);
  if (stored !== computed) {
    return { kind: 'bad', reason: `bad CRC in ${name} record (stored 0x${stored.toString(16).padStart(8, '0')}, computed 0x${computed.toString(16).padStart(8, '0')})` };
  }
  return { kind: 'frame', type: type as RecordTypeCode, payloadStart, payloadEnd, frameEnd };
}
