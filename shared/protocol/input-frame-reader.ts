// The fast path for the frame every playing client sends each tick: an input message whose fields are all msgpack
// integers ([2, firstTick, [[moveX, moveZ, yaw, pitch, buttons], …], ackTick?]). It reads those bytes straight into
// the same nested arrays msgpack decoding would give, so the one validator (decodeInput) checks them; any frame outside
// that narrow shape (floats, game values, 16 or more commands, another opcode, trailing bytes) gets null and takes the
// general path (scan, msgpackr, validation). It never accepts bytes the general path would read differently.
import { ClientOpcode } from './opcodes.ts';

let at = 0;

/** The msgpack integer at `at` (advancing past it), or NaN when the byte there starts anything else. */
function readInt(bytes: Uint8Array): number {
  const n = bytes.length;
  if (at >= n) return NaN;
  const b = bytes[at];
  if (b <= 0x7f) {
    at += 1;
    return b;
  }
  if (b >= 0xe0) {
    at += 1;
    return b - 0x100;
  }
  switch (b) {
    case 0xcc:
      if (at + 2 > n) return NaN;
      at += 2;
      return bytes[at - 1];
    case 0xcd:
      if (at + 3 > n) return NaN;
      at += 3;
      return (bytes[at - 2] << 8) | bytes[at - 1];
    case 0xce:
      if (at + 5 > n) return NaN;
      at += 5;
      return ((bytes[at - 4] << 24) >>> 0) + ((bytes[at - 3] << 16) | (bytes[at - 2] << 8) | bytes[at - 1]);
    case 0xd0:
      if (at + 2 > n) return NaN;
      at += 2;
      return (bytes[at - 1] << 24) >> 24;
    case 0xd1:
      if (at + 3 > n) return NaN;
      at += 3;
      return (((bytes[at - 2] << 8) | bytes[at - 1]) << 16) >> 16;
    case 0xd2:
      if (at + 5 > n) return NaN;
      at += 5;
      return (bytes[at - 4] << 24) | (bytes[at - 3] << 16) | (bytes[at - 2] << 8) | bytes[at - 1];
    default:
      return NaN;
  }
}

/**
 * The decoded fields of an all-integer input frame (what msgpack decoding of `bytes` returns), or null when `bytes`
 * are any other frame. Never throws.
 */
export function readInputFrame(bytes: Uint8Array): unknown[] | null {
  const n = bytes.length;
  if (n < 4) return null;
  const head = bytes[0];
  if ((head !== 0x93 && head !== 0x94) || bytes[1] !== ClientOpcode.Input) return null;
  at = 2;
  const firstTick = readInt(bytes);
  if (Number.isNaN(firstTick) || at >= n) return null;
  const listHead = bytes[at++];
  if (listHead < 0x91 || listHead > 0x9f) return null;
  const count = listHead & 0x0f;
  const commands: number[][] = new Array<number[]>(count);
  for (let i = 0; i < count; i++) {
    if (at >= n || bytes[at] !== 0x95) return null;
    at++;
    const moveX = readInt(bytes);
    const moveZ = readInt(bytes);
    const yaw = readInt(bytes);
    const pitch = readInt(bytes);
    const buttons = readInt(bytes);
    // NaN in any field poisons the sum: one test for the five.
    if (Number.isNaN(moveX + moveZ + yaw + pitch + buttons)) return null;
    commands[i] = [moveX, moveZ, yaw, pitch, buttons];
  }
  if (head === 0x93) return at === n ? [ClientOpcode.Input, firstTick, commands] : null;
  const ackTick = readInt(bytes);
  return !Number.isNaN(ackTick) && at === n ? [ClientOpcode.Input, firstTick, commands, ackTick] : null;
}
