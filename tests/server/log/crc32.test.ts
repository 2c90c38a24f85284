// Tests for the CRC-32 used by every input-log record: published check values and incremental use.
import { describe, expect, it } from 'vitest';
import { crc32, crc32Update } from '../../../server/log/crc32.ts';

const ascii = (s: string): Uint8Array => new TextEncoder().encode(s);

describe('crc32', () => {
  it('matches the published CRC-32/ISO-HDLC check values', () => {
    expect(crc32(ascii('123456789'))).toBe(0xcbf43926);
    expect(crc32(new Uint8Array(0))).toBe(0);
    expect(crc32(ascii('a'))).toBe(0xe8b7be43);
    expect(crc32(ascii('abc'))).toBe(0x352441c2);
    expect(crc32(ascii('The quick brown fox jumps over the lazy dog'))).toBe(0x414fa339);
    expect(crc32(new Uint8Array(32))).toBe(0x190a55ad);
    expect(crc32(new Uint8Array(32).fill(0xff))).toBe(0xff6cab0b);
  });

  it('gives the same result fed in pieces of any size as in one call', () => {
    const data = new Uint8Array(1000);
    for (let i = 0; i < data.length; i++) data[i] = (i * 131 + 7) & 0xff;
    const whole = crc32(data);
    for (const cut of [0, 1, 3, 4, 5, 499, 999, 1000]) {
      expect(crc32Update(crc32(data, 0, cut), data, cut, data.length)).toBe(whole);
    }
  });

  it('checks a sub-range without copying and rejects ranges outside the array', () => {
    const data = ascii('xx123456789yy');
    expect(crc32(data, 2, 11)).toBe(0xcbf43926);
    expect(() => crc32(data, 5, 40)).toThrow(/outside/);
  });

  it('changes when any single bit of the input flips', () => {
    const data = ascii('tick record payload');
    const base = crc32(data);
    for (let i = 0; i < data.length; i++) {
      for (let bit = 0; bit < 8; bit++) {
        const copy = data.slice();
        copy[i] ^= 1 << bit;
        expect(crc32(copy)).not.toBe(base);
      }
    }
  });
});
