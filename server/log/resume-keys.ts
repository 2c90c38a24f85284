// The resume keys beside a recording (`<log>.resume`): one line per resume token issued in the room, "playerId key",
// where the key is the token's SHA-256 (never the token itself), so that after a crash `serve --resume` can hand the
// same players back to the same clients. Written synchronously and fdatasynced before the welcome carrying the token
// leaves; the last line of a player wins.
import { closeSync, fdatasyncSync, openSync, readFileSync, writeSync } from 'node:fs';

/** The keys file of a log. */
export function resumeKeysPath(logPath: string): string {
  return `${logPath}.resume`;
}

const KEY_RE = /^[A-Za-z0-9_-]{43}$/;

/** Appends one player's key durably (throws on a write failure; the caller decides what that costs). */
export function appendResumeKey(logPath: string, playerId: number, key: string): void {
  if (!Number.isInteger(playerId) || playerId < 1 || !KEY_RE.test(key)) throw new Error(`bad resume key line for player ${playerId}`);
  const fd = openSync(resumeKeysPath(logPath), 'a');
  try {
    writeSync(fd, `${playerId} ${key}\n`);
    fdatasyncSync(fd);
  } finally {
    closeSync(fd);
  }
}

/** Each player's latest key; a missing file is an empty map, malformed lines (a torn last write) are skipped. */
export function readResumeKeys(logPath: string): Map<number, string> {
  let text: string;
  try {
    text = readFileSync(resumeKeysPath(logPath), 'utf8');
  } catch (err) {
    if ((err as NodeJS.ErrnoException).code === 'ENOENT') return new Map();
    throw err;
  }
  const keys = new Map<number, string>();
  for (const line of text.split('\n')) {
    const m = /^(\d{1,10}) (\S+)$/.exec(line);
    if (m && KEY_RE.test(m[2])) keys.set(Number(m[1]), m[2]);
  }
  return keys;
}
