// Tests for server/pretty-log.ts: pino's JSON lines become `time LEVEL message key=value` lines for a terminal.
import { describe, expect, it } from 'vitest';
import { prettyLogLine } from '../../server/pretty-log.ts';

describe('pretty-log', () => {
  it('writes UTC time, level, message and the fields that matter, quoting values with spaces', () => {
    const line = JSON.stringify({ level: 30, time: Date.UTC(2026, 0, 2, 3, 4, 5, 678), pid: 1, hostname: 'h', service: 'taos-physics', msg: 'player joined', room: 'default', player: 3, name: 'ann lee' });
    expect(prettyLogLine(line, false)).toBe('03:04:05.678 INFO  player joined  room=default player=3 name="ann lee"\n');
  });

  it('colours the level only when asked, and prints an error with its stack', () => {
    const line = JSON.stringify({ level: 50, time: 0, msg: 'tick failed', err: { type: 'Error', message: 'boom', stack: 'Error: boom\n    at x' } });
    expect(prettyLogLine(line, true)).toBe('00:00:00.000 \x1b[31mERROR\x1b[0m tick failed  err="boom"\nError: boom\n    at x\n');
    expect(prettyLogLine(line, false)).toMatch(/^00:00:00\.000 ERROR tick failed/);
  });

  it('passes a line that is not JSON through unchanged', () => {
    expect(prettyLogLine('not json', false)).toBe('not json\n');
  });
});
