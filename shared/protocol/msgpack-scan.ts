// Checks the structure of a msgpack frame before anything decodes it: exactly one value filling the buffer, made only
// of the plain types the protocol uses (nil, booleans, numbers, strings, binary, arrays, maps with string keys), no
// extension types (records, structured clones, typed arrays, dates, bigints…), no `__proto__` key, bounded nesting
// depth, and no declared length larger than the bytes that follow. Iterative: a hostile frame cannot overflow the stack.

let stackLeft = new Int32Array(65);
let stackMap = new Uint8Array(65);

/** Bytes of the key "__proto__" (9 ASCII bytes). */
const PROTO_KEY = [0x5f, 0x5f, 0x70, 0x72, 0x6f, 0x74, 0x6f, 0x5f, 0x5f];

function readLength(bytes: Uint8Array, at: number, size: 1 | 2 | 4): number {
  if (size === 1) return bytes[at];
  if (size === 2) return (bytes[at] << 8) | bytes[at + 1];
  return ((bytes[at] << 24) >>> 0) + ((bytes[at + 1] << 16) | (bytes[at + 2] << 8) | bytes[at + 3]);
}

function isProtoKey(bytes: Uint8Array, start: number, length: number): boolean {
  if (length !== PROTO_KEY.length) return false;
  for (let i = 0; i < length; i++) if (bytes[start + i] !== PROTO_KEY[i]) return false;
  return true;
}

/**
 * Returns null when `bytes` hold exactly one plain msgpack value nested at most `maxDepth` containers deep, or a
 * sentence saying what is wrong and at which byte offset. Never throws; reads each byte at most once.
 */
export function scanMsgpack(bytes: Uint8Array, maxDepth: number): string | null {
  const n = bytes.length;
  // One entry per open container: values still to read (checked against the bytes left first), and whether it is a
  // map (keys at even counts left). Reused between calls: a scan never runs inside another.
  if (maxDepth + 1 > stackLeft.length) {
    stackLeft = new Int32Array(maxDepth + 1);
    stackMap = new Uint8Array(maxDepth + 1);
  }
  const left = stackLeft;
  const isMap = stackMap;
  left[0] = 1;
  isMap[0] = 0;
  let depth = 1; // entries in use
  let pos = 0;
  while (depth > 0) {
    const top = depth - 1;
    if (left[top] === 0) {
      depth--;
      continue;
    }
    const atKey = isMap[top] === 1 && left[top] % 2 === 0;
    left[top]--;
    if (pos >= n) return `the frame ends at byte ${n} inside a value`;
    const at = pos;
    const b = bytes[pos++];
    let skip = 0; // payload bytes after the type byte (and length field)
    let strLength = -1; // ≥ 0 when the value is a string
    let items = -1; // ≥ 0 when the value is a container (values, keys included)
    let map = false;
    if (b <= 0x7f || b >= 0xe0) {
      // positive or negative fixint
    } else if (b <= 0x8f) {
      items = (b & 0x0f) * 2;
      map = true;
    } else if (b <= 0x9f) {
      items = b & 0x0f;
    } else if (b <= 0xbf) {
      strLength = b & 0x1f;
    } else {
      switch (b) {
        case 0xc0:
        case 0xc2:
        case 0xc3:
          break;
        case 0xc1:
          return `byte ${at}: 0xc1 is not a msgpack type`;
        case 0xc4:
        case 0xc5:
        case 0xc6: {
          const size = b === 0xc4 ? 1 : b === 0xc5 ? 2 : 4;
          if (pos + size > n) return `the frame ends at byte ${n} inside a binary length`;
          skip = readLength(bytes, pos, size);
          pos += size;
          break;
        }
        case 0xc7:
        case 0xc8:
        case 0xc9:
        case 0xd4:
        case 0xd5:
        case 0xd6:
        case 0xd7:
        case 0xd8:
          return `byte ${at}: msgpack extension types are not accepted`;
        case 0xca:
          skip = 4;
          break;
        case 0xcb:
          skip = 8;
          break;
        case 0xcc:
        case 0xd0:
          skip = 1;
          break;
        case 0xcd:
        case 0xd1:
          skip = 2;
          break;
        case 0xce:
        case 0xd2:
          skip = 4;
          break;
        case 0xcf:
        case 0xd3:
          skip = 8;
          break;
        case 0xd9:
        case 0xda:
        case 0xdb: {
          const size = b === 0xd9 ? 1 : b === 0xda ? 2 : 4;
          if (pos + size > n) return `the frame ends at byte ${n} inside a string length`;
          strLength = readLength(bytes, pos, size);
          pos += size;
          break;
        }
        case 0xdc:
        case 0xdd:
        case 0xde:
        case 0xdf: {
          const size = b === 0xdc || b === 0xde ? 2 : 4;
          if (pos + size > n) return `the frame ends at byte ${n} inside a container length`;
          map = b >= 0xde;
          items = readLength(bytes, pos, size) * (map ? 2 : 1);
          pos += size;
          break;
        }
        default:
          return `byte ${at}: unknown msgpack type 0x${b.toString(16)}`;
      }
    }
    if (atKey) {
      if (strLength < 0) return `byte ${at}: a map key must be a string`;
      if (pos + strLength <= n && isProtoKey(bytes, pos, strLength)) return `byte ${at}: the map key "__proto__" is not accepted`;
    }
    if (strLength >= 0) skip = strLength;
    if (skip > n - pos) return `byte ${at}: a value of ${skip} bytes, but only ${n - pos} follow`;
    pos += skip;
    if (items >= 0) {
      // Every value takes at least one byte: a larger count is a lie (and an allocation bomb for the decoder).
      if (items > n - pos) return `byte ${at}: a container of ${items} values, but only ${n - pos} bytes follow`;
      if (depth > maxDepth) return `byte ${at}: containers nest deeper than ${maxDepth}`;
      left[depth] = items;
      isMap[depth] = map ? 1 : 0;
      depth++;
    }
  }
  if (pos !== n) return `${n - pos} trailing byte(s) after the value (at byte ${pos})`;
  return null;
}
