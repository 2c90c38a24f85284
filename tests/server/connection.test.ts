// Tests for server/connection.ts: close reasons fit a WebSocket close frame.
import { describe, expect, it } from 'vitest';
import { clampCloseReason } from '../../server/connection.ts';

describe('connection', () => {
  it('cuts close reasons to the 123 bytes a close frame allows, on a character boundary', () => {
    expect(clampCloseReason('short')).toBe('short');
    const long = 'é'.repeat(100); // 200 bytes of UTF-8
    const cut = clampCloseReason(long);
    expect(new TextEncoder().encode(cut).length).toBeLessThanOrEqual(123);
    expect(cut.endsWith('…')).toBe(true);
    expect(cut.startsWith('éé')).toBe(true);
  });
});
