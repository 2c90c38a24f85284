// This process's entry in the fleet directory on Redis (ioredis): it registers itself (public URL, capacity, rooms,
// players) under a key with a TTL and refreshes it on a heartbeat, claims room ids fleet-wide (SET NX), and reads the
// other members. Redis being down or slow never blocks the tick loop or throws out of a timer: every call is bounded
// by a command timeout, failures are logged (once per outage) and retried on the next heartbeat, local rooms go on.
import { randomBytes } from 'node:crypto';
import type { Redis } from 'ioredis';
import type { Clock, TimerHandle } from '../../shared/clock.ts';
import { ErrorCode } from '../../shared/protocol/opcodes.ts';
import type { Logger } from '../logger.ts';
import { RoomError, type RoomInfo } from '../room.ts';
import type { RoomDirectory } from '../room-manager.ts';
import { RoomMovedError, webSocketUrl, type MemberAddress } from './room-moved.ts';

/** What a member publishes about itself. */
export interface MemberRecord extends MemberAddress {
  capacity: { rooms: number; connections: number };
  players: number;
  rooms: RoomInfo[];
  startedAt: string;
}

/** What this process publishes on each heartbeat (read when it is sent). */
export interface LocalState {
  capacity: { rooms: number; connections: number };
  players: number;
  rooms: RoomInfo[];
}

/** Options of FleetDirectory. */
export interface FleetDirectoryOptions {
  /** redis://[user:password@]host:port[/db] (or rediss:// for TLS). */
  redisUrl: string;
  /** A member (and its room claims) that stops refreshing disappears after this long. */
  ttlMs: number;
  /** Prefix of every key, so several fleets can share one Redis. */
  prefix: string;
  clock: Clock;
  logger: Logger;
  /** Longest wait for one Redis command (ms). Default 2000. */
  commandTimeoutMs?: number;
  /** ioredis's client class (loaded by the caller only when a fleet is asked for: it costs start-up time). */
  redisClass: typeof Redis;
}

/** Defaults of the fleet flags. */
export const FLEET_DEFAULTS = { ttlSeconds: 10, prefix: 'taos:' } as const;

// Refreshes this member's claims: its own keys get a new TTL, lost ones (Redis restarted) are taken again unless
// someone else holds them now; those are returned.
const REFRESH_CLAIMS = `
local lost = {}
for i, key in ipairs(KEYS) do
  local owner = redis.call('GET', key)
  if owner == ARGV[1] then redis.call('PEXPIRE', key, ARGV[2])
  elseif not owner then redis.call('SET', key, ARGV[1], 'PX', ARGV[2])
  else table.insert(lost, key) end
end
return lost`;
const RELEASE_CLAIM = `if redis.call('GET', KEYS[1]) == ARGV[1] then return redis.call('DEL', KEYS[1]) else return 0 end`;

function parseMember(text: string | null): MemberRecord | null {
  if (text === null) return null;
  try {
    const v = JSON.parse(text) as MemberRecord;
    if (typeof v.id !== 'string' || typeof v.url !== 'string' || typeof v.wsUrl !== 'string' || !Array.isArray(v.rooms)) return null;
    return v;
  } catch {
    return null;
  }
}

const errorText = (error: unknown): string => (error instanceof Error ? error.message : String(error));

/** One process's membership of the fleet. */
export class FleetDirectory implements RoomDirectory {
  /** This member's id (random per process start). */
  readonly id = randomBytes(6).toString('hex');
  private urlValue = '';
  private wsUrlValue = '';
  private readonly opts: FleetDirectoryOptions;
  private readonly redis: Redis;
  private readonly claims = new Set<string>();
  private readonly startedAt = new Date().toISOString();
  private local: (() => LocalState) | null = null;
  private heartbeat: TimerHandle | null = null;
  private soon: TimerHandle | null = null;
  private cache: MemberRecord[] = [];
  private failing = false;
  private closed = false;

  constructor(opts: FleetDirectoryOptions) {
    this.opts = opts;
    const timeoutMs = opts.commandTimeoutMs ?? 2000;
    this.redis = new opts.redisClass(opts.redisUrl, {
      lazyConnect: true,
      // Commands fail at once while disconnected (nothing queues up behind an outage) and never wait past the timeout.
      enableOfflineQueue: false,
      commandTimeout: timeoutMs,
      connectTimeout: Math.max(timeoutMs, 2000),
      maxRetriesPerRequest: 0,
      retryStrategy: (times) => Math.min(100 * times, 2000),
    });
    this.redis.on('error', (error: Error) => this.trouble('the fleet directory (Redis) is unreachable', error));
    this.redis.on('ready', () => {
      if (this.closed) return;
      this.opts.logger.info({ redis: this.redisHost(), member: this.id }, 'fleet directory connected');
      this.publishSoon();
    });
  }

  /** Where players reach this process (set by start). */
  get url(): string {
    return this.urlValue;
  }

  /** Its WebSocket URL. */
  get wsUrl(): string {
    return this.wsUrlValue;
  }

  private get ttlMs(): number {
    return this.opts.ttlMs;
  }

  private key(kind: 'member' | 'room', id: string): string {
    return `${this.opts.prefix}${kind}:${id}`;
  }

  private get membersKey(): string {
    return `${this.opts.prefix}members`;
  }

  /** Redis host and port for logs (never the password). */
  private redisHost(): string {
    try {
      const u = new URL(this.opts.redisUrl);
      return `${u.hostname}:${u.port || 6379}`;
    } catch {
      return 'redis';
    }
  }

  /** Logs the first failure of an outage (later ones are quiet until it recovers). */
  private trouble(what: string, error: unknown): void {
    if (this.closed || this.failing) return;
    this.failing = true;
    this.opts.logger.warn({ redis: this.redisHost(), err: errorText(error) }, `${what}: serving local rooms, retrying`);
  }

  private recovered(): void {
    if (!this.failing) return;
    this.failing = false;
    this.opts.logger.info({ redis: this.redisHost() }, 'fleet directory reachable again');
  }

  /**
   * Joins the fleet as `publicUrl` (http:// or https://, where players reach this process) and starts the heartbeat
   * with what to publish; waits (bounded) for the first registration but never fails for Redis.
   */
  async start(publicUrl: string, local: () => LocalState): Promise<void> {
    this.urlValue = new URL(publicUrl).href;
    this.wsUrlValue = webSocketUrl(this.urlValue);
    this.local = local;
    this.redis.connect().catch((error: unknown) => this.trouble('cannot connect to the fleet directory (Redis)', error));
    const beat = (): void => {
      this.heartbeat = this.opts.clock.setTimer(Math.max(100, Math.floor(this.ttlMs / 3)), beat);
      void this.publish();
    };
    this.heartbeat = this.opts.clock.setTimer(Math.max(100, Math.floor(this.ttlMs / 3)), beat);
    await new Promise<void>((resolve) => {
      if (this.redis.status === 'ready') return resolve();
      const done = (): void => {
        this.redis.off('ready', done);
        this.opts.clock.clearTimer(timer);
        resolve();
      };
      const timer = this.opts.clock.setTimer(2000, done);
      this.redis.once('ready', done);
    });
    await this.publish();
  }

  /** Publishes soon (a room opened or closed): coalesced into one write. */
  private publishSoon(): void {
    if (this.soon !== null || this.closed) return;
    this.soon = this.opts.clock.setTimer(20, () => {
      this.soon = null;
      void this.publish();
    });
  }

  private record(): MemberRecord | null {
    if (!this.local) return null;
    const state = this.local();
    return { id: this.id, url: this.url, wsUrl: this.wsUrl, capacity: state.capacity, players: state.players, rooms: state.rooms, startedAt: this.startedAt };
  }

  /** Writes this member's record and refreshes its claims; never throws. */
  async publish(): Promise<void> {
    const record = this.record();
    if (this.closed || record === null || this.redis.status !== 'ready') return;
    const claimKeys = [...this.claims].map((id) => this.key('room', id));
    try {
      const results = await this.redis
        .multi()
        .set(this.key('member', this.id), JSON.stringify(record), 'PX', this.ttlMs)
        .sadd(this.membersKey, this.id)
        .eval(REFRESH_CLAIMS, claimKeys.length, ...claimKeys, this.id, String(this.ttlMs))
        .exec();
      const lost = (results?.[2]?.[1] ?? []) as string[];
      if (lost.length > 0) this.opts.logger.error({ keys: lost }, 'another server of the fleet claimed ids of rooms open here (the directory lost them during an outage): two rooms now share an id');
      this.recovered();
    } catch (error) {
      this.trouble('cannot refresh this server in the fleet directory (Redis)', error);
    }
  }

  private unavailable(id: string, error: unknown): RoomError {
    this.trouble('the fleet directory (Redis) did not answer', error);
    return new RoomError(ErrorCode.ServerFull, `cannot open room ${JSON.stringify(id)} now: the fleet directory does not answer (room ids are unique across the fleet); try again shortly`);
  }

  /** The refusal for a room another member holds: where it is, or that its holder stopped answering. */
  private async heldElsewhere(id: string, owner: string): Promise<RoomError> {
    const member = parseMember(await this.redis.get(this.key('member', owner)));
    if (member) return new RoomMovedError(id, { id: member.id, url: member.url, wsUrl: member.wsUrl });
    return new RoomError(ErrorCode.ServerFull, `room ${JSON.stringify(id)} is held by a server of the fleet that stopped answering; its claim lapses within ${Math.ceil(this.ttlMs / 1000)} s`);
  }

  async claim(id: string): Promise<void> {
    let owner: string | null = null;
    try {
      // Twice at most: a claim that lapses between our SET and GET leaves the id free for a second SET.
      for (let attempt = 0; attempt < 2 && owner === null; attempt++) {
        if ((await this.redis.set(this.key('room', id), this.id, 'PX', this.ttlMs, 'NX')) === 'OK') owner = this.id;
        else owner = await this.redis.get(this.key('room', id));
      }
    } catch (error) {
      throw this.unavailable(id, error);
    }
    if (owner === null) throw new RoomError(ErrorCode.ServerFull, `room ${JSON.stringify(id)} is being opened and closed elsewhere in the fleet; try again`);
    if (owner === this.id) {
      this.claims.add(id);
      return;
    }
    let refusal: RoomError;
    try {
      refusal = await this.heldElsewhere(id, owner);
    } catch (error) {
      throw this.unavailable(id, error);
    }
    throw refusal;
  }

  opened(_id: string): void {
    this.publishSoon();
  }

  release(id: string): void {
    this.claims.delete(id);
    this.publishSoon();
    if (this.redis.status !== 'ready') return; // it lapses within the TTL
    this.redis.eval(RELEASE_CLAIM, 1, this.key('room', id), this.id).catch((error: unknown) => this.trouble('cannot release a room id in the fleet directory', error));
  }

  async locate(id: string): Promise<void> {
    let owner: string | null;
    try {
      owner = await this.redis.get(this.key('room', id));
    } catch (error) {
      this.trouble('the fleet directory (Redis) did not answer', error);
      return; // unknown here; the claim that opening it needs will refuse clearly if Redis is still down
    }
    if (owner === null || owner === this.id) return;
    let refusal: RoomError;
    try {
      refusal = await this.heldElsewhere(id, owner);
    } catch (error) {
      this.trouble('the fleet directory (Redis) did not answer', error);
      return;
    }
    throw refusal;
  }

  /** Every live member (this one included), read now; members whose record lapsed are pruned from the index. */
  async members(): Promise<MemberRecord[]> {
    const ids = (await this.redis.smembers(this.membersKey)).sort();
    if (ids.length === 0) return [];
    const texts = await this.redis.mget(ids.map((id) => this.key('member', id)));
    const out: MemberRecord[] = [];
    const gone: string[] = [];
    ids.forEach((id, i) => {
      const m = parseMember(texts[i] ?? null);
      if (m) out.push(m);
      else gone.push(id);
    });
    if (gone.length > 0) this.redis.srem(this.membersKey, ...gone).catch(() => undefined);
    this.cache = out;
    return out;
  }

  /** For /healthz: this member and whether Redis answers (the server stays healthy without it: local rooms go on). */
  status(): { member: string; url: string; redis: 'connected' | 'unreachable' } {
    return { member: this.id, url: this.url, redis: this.redis.status === 'ready' && !this.failing ? 'connected' : 'unreachable' };
  }

  /** The members as last read (possibly stale; empty before the first read). */
  cachedMembers(): readonly MemberRecord[] {
    return this.cache;
  }

  /** Leaves the fleet: stops the heartbeat, removes this member and its claims (bounded), closes the connection. */
  async close(): Promise<void> {
    if (this.closed) return;
    if (this.heartbeat) this.opts.clock.clearTimer(this.heartbeat);
    if (this.soon) this.opts.clock.clearTimer(this.soon);
    this.heartbeat = null;
    this.soon = null;
    if (this.redis.status === 'ready') {
      const claimKeys = [...this.claims].map((id) => this.key('room', id));
      try {
        const tx = this.redis.multi().del(this.key('member', this.id)).srem(this.membersKey, this.id);
        for (const k of claimKeys) tx.eval(RELEASE_CLAIM, 1, k, this.id);
        await tx.exec();
      } catch (error) {
        this.opts.logger.warn({ err: errorText(error) }, 'cannot remove this server from the fleet directory; it lapses within the TTL');
      }
    }
    this.closed = true;
    this.claims.clear();
    this.redis.disconnect();
  }
}
