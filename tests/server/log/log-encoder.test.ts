// Tests of server/log/log-encoder.ts: a known session encodes to the same bytes as ever (a format pin: any change to
// the record codec or the byte writer that alters one byte of the log fails here).
import { createHash } from 'node:crypto';
import { describe, expect, it } from 'vitest';
import { buildLog } from '../../helpers/input-log.ts';

describe('LogEncoder', () => {
  it('encodes a known session with ticks, joins, leaves, hashes, checkpoints and an end to pinned bytes', () => {
    const bytes = buildLog(60, { players: 3, checkpointEvery: 20 });
    expect({ sizeBytes: bytes.length, sha256: createHash('sha256').update(bytes).digest('hex') }).toEqual({ sizeBytes: 3557, sha256: '6bb62c55fd42c1f1db89dc24a8938590fbc49feb19ea17a990879130c5d9c650' });
  });
});
