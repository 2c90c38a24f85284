// Tests for wire-size arithmetic: WebSocket header lengths at their boundaries and kilobits per second.
import { describe, expect, it } from 'vitest';
import { kbps, wsClientFrameBytes, wsFrameBytes } from '../../../bench/lib/wire.ts';

describe('wire', () => {
  it('adds 2, 4 or 10 header bytes by payload length (RFC 6455)', () => {
    expect(wsFrameBytes(0)).toBe(2);
    expect(wsFrameBytes(125)).toBe(127);
    expect(wsFrameBytes(126)).toBe(130);
    expect(wsFrameBytes(65535)).toBe(65539);
    expect(wsFrameBytes(65536)).toBe(65546);
  });

  it('adds the 4-byte mask to client frames', () => {
    expect(wsClientFrameBytes(10)).toBe(16);
  });

  it('converts bytes over seconds to kilobits per second', () => {
    expect(kbps(16_000, 1)).toBe(128);
    expect(kbps(960_000, 60)).toBe(128);
  });

  it('refuses impossible inputs', () => {
    expect(() => wsFrameBytes(-1)).toThrow(/byte count/);
    expect(() => kbps(10, 0)).toThrow(/seconds must be > 0/);
  });
});
