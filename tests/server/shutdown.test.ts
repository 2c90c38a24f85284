// Tests for server/shutdown.ts: a signal closes the target with the reason and exits 0; a second signal exits 1.
import { EventEmitter } from 'node:events';
import { describe, expect, it } from 'vitest';
import { silentLogger } from '../../server/logger.ts';
import { installShutdown } from '../../server/shutdown.ts';

describe('shutdown', () => {
  it('closes the server with the signal as the reason, then exits 0', async () => {
    const source = new EventEmitter();
    const reasons: string[] = [];
    const exits: number[] = [];
    const { done } = installShutdown(
      { close: async (reason) => void reasons.push(reason) },
      { logger: silentLogger(), source, exit: (c) => exits.push(c) },
    );
    source.emit('SIGTERM');
    expect(await done).toBe(0);
    expect(reasons).toEqual(['server shutting down (SIGTERM)']);
    expect(exits).toEqual([0]);
  });

  it('exits 1 on a second signal while a close is still running', async () => {
    const source = new EventEmitter();
    const exits: number[] = [];
    const { done } = installShutdown({ close: () => new Promise(() => {}) }, { logger: silentLogger(), source, exit: (c) => exits.push(c) });
    source.emit('SIGINT');
    source.emit('SIGINT');
    expect(await done).toBe(1);
    expect(exits[0]).toBe(1);
  });

  it('exits 1 when the close fails or hangs past the limit', async () => {
    const failing = new EventEmitter();
    const a = installShutdown({ close: async () => Promise.reject(new Error('disk full')) }, { logger: silentLogger(), source: failing, exit: () => {} });
    failing.emit('SIGTERM');
    expect(await a.done).toBe(1);
    const hanging = new EventEmitter();
    const b = installShutdown({ close: () => new Promise(() => {}) }, { logger: silentLogger(), source: hanging, exit: () => {}, forceAfterMs: 20 });
    hanging.emit('SIGTERM');
    expect(await b.done).toBe(1);
  });

  it('removes its handlers on uninstall', () => {
    const source = new EventEmitter();
    const { uninstall } = installShutdown({ close: async () => {} }, { logger: silentLogger(), source, exit: () => {} });
    expect(source.listenerCount('SIGTERM')).toBe(1);
    uninstall();
    expect(source.listenerCount('SIGTERM')).toBe(0);
    expect(source.listenerCount('SIGINT')).toBe(0);
  });
});
