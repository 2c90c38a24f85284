// Unit tests of server/fleet/agones-lifecycle.ts on a manual clock with a recording SDK client: when it allocates,
// drains and shuts down, what it publishes, and where Agones says players reach the GameServer.
import { describe, expect, it } from 'vitest';
import { ManualClock } from '../../../shared/clock.ts';
import { AgonesLifecycle, gameServerUrl, type AgonesClient, type AgonesGameServer, type WatchedRooms } from '../../../server/fleet/agones-lifecycle.ts';
import { silentLogger } from '../../../server/logger.ts';
import type { Room } from '../../../server/room.ts';

/** A room with a player count that tells its listeners when it empties or fills, and closes. */
class FakeRoom {
  readonly id: string;
  players = 0;
  private readonly empty = new Set<(empty: boolean) => void>();
  private readonly close = new Set<(reason: string) => void>();
  constructor(id: string) {
    this.id = id;
  }
  onEmptyChange(fn: (empty: boolean) => void): () => void {
    this.empty.add(fn);
    return () => this.empty.delete(fn);
  }
  onClose(fn: (reason: string) => void): () => void {
    this.close.add(fn);
    return () => this.close.delete(fn);
  }
  setPlayers(n: number): void {
    const was = this.players;
    this.players = n;
    if ((was === 0) !== (n === 0)) this.empty.forEach((fn) => fn(n === 0));
  }
  closeRoom(): void {
    this.close.forEach((fn) => fn('closed'));
  }
}

class FakeRooms implements WatchedRooms {
  readonly rooms = new Map<string, FakeRoom>();
  private readonly opened = new Set<(room: Room) => void>();
  all(): Room[] {
    return [...this.rooms.values()] as unknown as Room[];
  }
  clientCount(): number {
    let n = 0;
    for (const r of this.rooms.values()) n += r.players;
    return n;
  }
  onRoomOpened(fn: (room: Room) => void): () => void {
    this.opened.add(fn);
    return () => this.opened.delete(fn);
  }
  open(id: string): FakeRoom {
    const room = new FakeRoom(id);
    this.rooms.set(id, room);
    this.opened.forEach((fn) => fn(room as unknown as Room));
    return room;
  }
  closeRoom(id: string): void {
    const room = this.rooms.get(id)!;
    this.rooms.delete(id);
    room.closeRoom();
  }
}

function fakeClient(opts: { countsDeclared: boolean }): AgonesClient & { calls: string[] } {
  const calls: string[] = [];
  const notDeclared = (): Promise<void> => Promise.reject(new Error('5 NOT_FOUND: not declared'));
  return {
    calls,
    connect: async () => undefined,
    ready: async () => void calls.push('Ready'),
    allocate: async () => void calls.push('Allocate'),
    shutdown: async () => void calls.push('Shutdown'),
    health: () => void calls.push('Health'),
    setLabel: async (k, v) => void calls.push(`label ${k}=${v}`),
    getGameServer: async () => ({}),
    watchGameServer: () => undefined,
    close: () => void calls.push('close'),
    beta: {
      setCounterCount: (k, n) => (opts.countsDeclared ? Promise.resolve(void calls.push(`counter ${k}=${n}`)) : notDeclared()),
      setCounterCapacity: (k, n) => (opts.countsDeclared ? Promise.resolve(void calls.push(`capacity ${k}=${n}`)) : notDeclared()),
      appendListValue: (k, v) => (opts.countsDeclared ? Promise.resolve(void calls.push(`list+ ${k} ${v}`)) : notDeclared()),
      deleteListValue: (k, v) => (opts.countsDeclared ? Promise.resolve(void calls.push(`list- ${k} ${v}`)) : notDeclared()),
    },
  };
}

const settle = async (): Promise<void> => {
  for (let i = 0; i < 50; i++) await Promise.resolve();
};

async function started(singleSession: boolean, countsDeclared = true) {
  const clock = new ManualClock();
  const rooms = new FakeRooms();
  const def = rooms.open('default');
  const client = fakeClient({ countsDeclared });
  const over: string[] = [];
  const lifecycle = new AgonesLifecycle({ client, rooms, clock, logger: silentLogger(), singleSession, drainMs: 5000, healthIntervalMs: 1000, maxPlayers: 32, onSessionOver: (r) => over.push(r) });
  await lifecycle.connect();
  await lifecycle.start();
  clock.advance(100);
  await settle();
  return { clock, rooms, def, client, over, lifecycle };
}

describe('AgonesLifecycle', () => {
  it('marks Ready, pings Health on its interval and publishes players, rooms and the counter capacity', async () => {
    const { clock, client } = await started(false);
    expect(client.calls.slice(0, 2)).toEqual(['Ready', 'Health']);
    expect(client.calls).toEqual(expect.arrayContaining(['capacity players=32', 'label players=0', 'counter players=0', 'label rooms=1', 'list+ rooms default']));
    const pings = client.calls.filter((c) => c === 'Health').length;
    clock.advance(3000);
    expect(client.calls.filter((c) => c === 'Health').length).toBe(pings + 3);
  });

  it('allocates a single-session server once, on its first player, and never a multi-session one', async () => {
    const single = await started(true);
    single.def.setPlayers(1);
    single.rooms.open('arena').setPlayers(2);
    await settle();
    expect(single.client.calls.filter((c) => c === 'Allocate')).toEqual(['Allocate']);
    expect(single.lifecycle.isAllocated).toBe(true);
    const multi = await started(false);
    multi.def.setPlayers(3);
    await settle();
    expect(multi.client.calls).not.toContain('Allocate');
  });

  it('ends a finished session after the drain, unless a player comes back during it', async () => {
    const { clock, rooms, def, over } = await started(true);
    const arena = rooms.open('arena');
    arena.setPlayers(1);
    await settle();
    arena.setPlayers(0);
    rooms.closeRoom('arena');
    clock.advance(10);
    def.setPlayers(0);
    clock.advance(4000);
    def.setPlayers(1); // back within the drain
    clock.advance(10_000);
    expect(over).toEqual([]);
    def.setPlayers(0);
    clock.advance(4999);
    expect(over).toEqual([]);
    clock.advance(1);
    expect(over).toEqual(['the session is over (no players, no rooms)']);
  });

  it('keeps only labels when the GameServer declares no counter or list', async () => {
    const { client, def, clock } = await started(false, false);
    def.setPlayers(2);
    clock.advance(100);
    await settle();
    expect(client.calls).toContain('label players=2');
    expect(client.calls.some((c) => c.startsWith('counter') || c.startsWith('list'))).toBe(false);
  });

  it('calls Shutdown once and closes the SDK link', async () => {
    const { lifecycle, client } = await started(false);
    await Promise.all([lifecycle.shutdown('SIGTERM'), lifecycle.shutdown('again')]);
    expect(client.calls.filter((c) => c === 'Shutdown' || c === 'close')).toEqual(['Shutdown', 'close']);
  });
});

describe('gameServerUrl', () => {
  it('builds the public URL from the GameServer address and its first assigned port', () => {
    const gs: AgonesGameServer = { status: { address: '34.1.2.3', portsList: [{ name: 'default', port: 7601 }] } };
    expect(gameServerUrl(gs, false)).toBe('http://34.1.2.3:7601/');
    expect(gameServerUrl({ status: { address: '2001:db8::1', portsList: [{ port: 7602 }] } }, true)).toBe('https://[2001:db8::1]:7602/');
  });

  it('answers null while Agones has assigned no address or port', () => {
    expect(gameServerUrl({ status: { address: '', portsList: [{ port: 7601 }] } }, false)).toBeNull();
    expect(gameServerUrl({ status: { address: '10.0.0.1', portsList: [] } }, false)).toBeNull();
    expect(gameServerUrl({}, false)).toBeNull();
  });
});
