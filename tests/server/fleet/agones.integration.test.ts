// The Agones lifecycle through the official SDK against a local stand-in of its sidecar (tests/helpers/agones-sidecar.ts,
// built from the gRPC definitions inside the npm SDK; there is no Kubernetes here): Ready, Health, the players counter,
// rooms list and labels, Allocate on the first player of a single-session server, Shutdown after the drain or on SIGTERM.
import { afterEach, describe, expect, it } from 'vitest';
import { startAgonesSidecar, type AgonesSidecar } from '../../helpers/agones-sidecar.ts';
import { startServeProcess, type ServeProcess } from '../../helpers/serve-process.ts';
import { WsTestClient } from '../ws-client.ts';

// The servers run as `serve` child processes, so the CLI's flags, environment detection and exit are covered too.
let sidecar: AgonesSidecar | null = null;
let proc: ServeProcess | null = null;

afterEach(async () => {
  await proc?.stop('SIGKILL');
  await sidecar?.stop();
  proc = null;
  sidecar = null;
});

async function until(pred: () => boolean, timeoutMs: number, what: string): Promise<void> {
  const start = performance.now();
  while (!pred()) {
    if (performance.now() - start > timeoutMs) throw new Error(`timed out after ${timeoutMs} ms waiting until ${what}`);
    await new Promise((r) => setTimeout(r, 10));
  }
}

describe('the Agones lifecycle of `serve` (official SDK, stand-in sidecar)', () => {
  it('goes Ready with Health, publishes players and rooms, Allocates on the first player, Shuts down after the drain and exits', async () => {
    const sc = (sidecar = await startAgonesSidecar({ counters: { players: 1000 }, lists: { rooms: 100 } }));
    const server = (proc = await startServeProcess(['--agones-single-session', '--agones-drain', '1', '--max-connections', '64', '--log-level', 'warn', '--client-dir', '/nonexistent'], { AGONES_SDK_GRPC_PORT: String(sc.port) }));
    expect(sc.calls[0]).toBe('Ready');
    expect(sc.state.state).toBe('Ready');
    await until(() => sc.state.healthPings >= 1, 10_000, 'a Health ping');
    await until(() => sc.state.lists.get('rooms')?.values.join() === 'default' && sc.state.labels.get('agones.dev/sdk-rooms') === '1', 5000, 'the rooms list and label');
    expect(sc.state.counters.get('players')).toEqual({ count: 0, capacity: 64 });
    expect(sc.state.labels.get('agones.dev/sdk-players')).toBe('0');

    const player = await WsTestClient.join(server.wsUrl, 'Ada');
    await until(() => sc.state.state === 'Allocated', 5000, 'Allocated');
    await until(() => sc.state.counters.get('players')?.count === 1 && sc.state.labels.get('agones.dev/sdk-players') === '1', 5000, 'one player counted');
    expect(sc.calls.filter((c) => c === 'Allocate')).toHaveLength(1);

    // The player leaves; the drain passes with nobody back; the server shuts down and the process exits by itself.
    player.close();
    expect(await server.exited(15_000)).toBe(0);
    expect(sc.state.state).toBe('Shutdown');
    const order = ['Ready', 'Health', 'Allocate', 'Shutdown'].map((c) => sc.calls.indexOf(c));
    expect(order).toEqual([...order].sort((x, y) => x - y));
    // Nothing is published after Shutdown (a Health ping already on its way may still land).
    expect(sc.calls.slice(sc.calls.indexOf('Shutdown') + 1).filter((c) => c !== 'Health')).toEqual([]);
  });

  it('with only the sidecar\'s environment: no Allocate of its own, follows an allocation from outside, labels without counters, Shutdown on SIGTERM', async () => {
    const sc = (sidecar = await startAgonesSidecar({}));
    const server = (proc = await startServeProcess(['--log-level', 'info', '--client-dir', '/nonexistent'], { AGONES_SDK_GRPC_PORT: String(sc.port) }));
    expect(sc.state.state).toBe('Ready');
    await until(() => sc.state.healthPings >= 1, 10_000, 'a Health ping');
    const player = await WsTestClient.join(server.wsUrl, 'Bo');
    await until(() => sc.state.labels.get('agones.dev/sdk-players') === '1', 5000, 'the players label');
    expect(sc.calls).not.toContain('Allocate');
    expect(server.log()).toContain('publishing labels only');
    sc.allocateFromOutside();
    await until(() => server.log().includes('agones: Allocated'), 5000, 'the server sees the allocation');
    player.close();
    await server.stop('SIGTERM');
    expect(sc.state.state).toBe('Shutdown');
    // Nothing is published after Shutdown (a Health ping already on its way may still land).
    expect(sc.calls.slice(sc.calls.indexOf('Shutdown') + 1).filter((c) => c !== 'Health')).toEqual([]);
  });
});
