// CRC-32 (IEEE 802.3, reflected polynomial 0xEDB88320), table-driven with slicing-by-4: the checksum of every
// input-log record. Pure arithmetic on Uint8Array; no Node APIs, so it can move to shared/ unchanged.

function makeTables(): Uint32Array[] {
  const t0 = new Uint32Array(256);
  for (let n = 0; n < 256; n++) {
    let c = n;
    for (let k = 0; k < 8; k++) c = c & 1 ? 0xedb88320 ^ (c >>> 1) : c >>> 1;
    t0[n] = c >>> 0;
  }
  const tables = [t0];
  for (let s = 1; s < 4; s++) {
    const prev = tables[s - 1];
    const t = new Uint32Array(256);
    for (let n = 0; n < 256; n++) t[n] = (t0[prev[n] & 0xff] ^ (prev[n] >>> 8)) >>> 0;
    tables.push(t);
  }
  return tables;
}

const [T0, T1, T2, T3] = makeTables();

/**
 * Continues a CRC-32 over bytes[start, end). Pass the previous call's result as `crc` (start from 0); the result is
 * the finished CRC of everything fed so far, as an unsigned 32-bit integer.
 */
export function crc32Update(crc: number, bytes: Uint8Array, start = 0, end = bytes.length): number {
  if (start < 0 || end > bytes.length || start > end) throw new RangeError(`crc32: range [${start}, ${end}) outside 0..${bytes.length}`);
  let c = ~crc >>> 0;
  let i = start;
  const fourEnd = end - ((end - start) & 3);
  for (; i < fourEnd; i += 4) {
    c ^= bytes[i] | (bytes[i + 1] << 8) | (bytes[i + 2] << 16) | (bytes[i + 3] << 24);
    c = T3[c & 0xff] ^ T2[(c >>> 8) & 0xff] ^ T1[(c >>> 16) & 0xff] ^ T0[c >>> 24];
  }
  for (; i < end; i++) c = T0[(c ^ bytes[i]) & 0xff] ^ (c >>> 8);
  return ~c >>> 0;
}

/** CRC-32 of bytes[start, end) as an unsigned 32-bit integer (crc32 of ASCII "123456789" is 0xCBF43926). */
export function crc32(bytes: Uint8Array, start = 0, end = bytes.length): number {
  return crc32Update(0, bytes, start, end);
}
