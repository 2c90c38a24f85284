// Tests of server/log/log-encoder.ts: a known session encodes to the same bytes as ever (a format pin: any change to
// the record codec or the byte writer that alters one byte of the log fails here).
import { createHash } from 'node:crypto';
import { describe, expect, it } from 'vitest';
import { buildLog } from '../../helpers/input-log.ts';

describe('LogEncoder', () => {
  // Format version 2 (the header's scenario hash) moved the pin; version-1 logs are still read.
  it('encodes a known session with ticks, joins, leaves, hashes, checkpoints and an end to pinned bytes', () => {
    const bytes = buildLog(60, { players: 3, checkpointEvery: 20 });
    expect({ sizeBytes: bytes.length, sha256: createHash('sha256').update(bytes).digest('hex') }).toEqual({ sizeBytes: 3558, sha256: '4ddc2e1143cebaaf0f7fac625cfb97dce273fa975c0a680c9e8d6b4a8707fd1e' });
  });
});
