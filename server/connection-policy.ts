// Who may open a WebSocket now: per-address caps on open sockets and on sockets that have not said hello, a cap on
// all sockets, and a growing refusal period for an address whose clients keep getting kicked. Pure bookkeeping on a
// Clock; the ws gateway asks before each upgrade and reports each socket's hello, kick and end.
import type { Clock } from '../shared/clock.ts';

/** Limits of the connection policy (every one has a default; see DEFAULT_CONNECTION_POLICY). */
export interface ConnectionPolicyOptions {
  /** Most open sockets per client address (IPv6: per /64), counted until the socket is gone. */
  maxSocketsPerAddress: number;
  /** Most sockets per address that have not said hello yet. */
  maxPendingPerAddress: number;
  /** Most open sockets in all (counted like the per-address ones: a kicked socket counts until it is gone). */
  maxSockets: number;
  /** Kicks (flood, invalid messages, no hello in time, oversize frames) an address may collect before refusals. */
  kicksBeforeBackoff: number;
  /** Refusal period after the kick that reaches kicksBeforeBackoff; each further kick doubles it. */
  backoffBaseMs: number;
  /** Longest refusal period. */
  backoffMaxMs: number;
  /** An address's kicks are forgotten after this long without another. */
  kickMemoryMs: number;
  /** Most addresses remembered at once (those with open sockets are never forgotten). */
  maxTrackedAddresses: number;
}

/** Defaults: room for a LAN party behind one NAT (32 players), a short leash on half-open and misbehaving clients. */
export const DEFAULT_CONNECTION_POLICY: Readonly<ConnectionPolicyOptions> = Object.freeze({
  maxSocketsPerAddress: 32,
  maxPendingPerAddress: 8,
  maxSockets: 256,
  kicksBeforeBackoff: 3,
  backoffBaseMs: 2_000,
  backoffMaxMs: 60_000,
  kickMemoryMs: 60_000,
  maxTrackedAddresses: 65_536,
});

/** Why an upgrade is refused (the label of taos_connections_refused_total). */
export const RefusalReason = {
  /** The address has maxSocketsPerAddress sockets open. */
  AddressSockets: 'address-sockets',
  /** The address has maxPendingPerAddress sockets that have not said hello. */
  AddressPending: 'address-pending',
  /** The address's clients were kicked too often; it is refused for a while. */
  Backoff: 'backoff',
  /** maxSockets sockets are open. */
  ServerFull: 'server-full',
} as const;
export type RefusalReason = (typeof RefusalReason)[keyof typeof RefusalReason];

/** A refused upgrade: why, a sentence, and when trying again may work. */
export interface Refusal {
  reason: RefusalReason;
  message: string;
  retryAfterMs: number;
}

interface AddressState {
  sockets: number;
  pending: number;
  kicks: number;
  lastKickMs: number;
  refusedUntilMs: number;
}

/** One admitted socket's account with the policy; every method is idempotent where it matters. */
export interface ConnectionTicket {
  readonly key: string;
  /** The client said hello: it no longer counts as pending. */
  helloed(): void;
  /** The server kicked the client for misbehaving (counts towards the address's back-off). */
  kicked(): void;
  /** The socket is gone: it no longer counts at all. */
  closed(): void;
}

/** The per-address bookkeeping. */
export class ConnectionPolicy {
  readonly options: Readonly<ConnectionPolicyOptions>;
  private readonly clock: Clock;
  private readonly addresses = new Map<string, AddressState>();
  private sockets = 0;

  constructor(clock: Clock, options: Partial<ConnectionPolicyOptions> = {}) {
    const o = { ...DEFAULT_CONNECTION_POLICY, ...options };
    for (const [k, v] of Object.entries(o)) {
      if (!(typeof v === 'number' && v >= 0 && (Number.isInteger(v) || v === Infinity))) throw new Error(`connection policy: ${k} must be a whole number ≥ 0, got ${String(v)}`);
    }
    this.clock = clock;
    this.options = Object.freeze(o);
  }

  /** Open sockets in all. */
  get openSockets(): number {
    return this.sockets;
  }

  /** Addresses currently remembered (open sockets, or kicks not yet forgotten). */
  get trackedAddresses(): number {
    return this.addresses.size;
  }

  /** The socket and pending counts of one address key (zeros when unknown). */
  countsOf(key: string): { sockets: number; pending: number; kicks: number } {
    const s = this.addresses.get(key);
    return { sockets: s?.sockets ?? 0, pending: s?.pending ?? 0, kicks: s ? this.liveKicks(s) : 0 };
  }

  /** How long `key` stays refused for its kicks (0 when it is not). */
  backoffRemainingMs(key: string): number {
    const s = this.addresses.get(key);
    return s ? Math.max(0, Math.ceil(s.refusedUntilMs - this.clock.nowMs())) : 0;
  }

  /** Null when a socket from `key` may open now, else why not. */
  admit(key: string): Refusal | null {
    const o = this.options;
    const s = this.addresses.get(key);
    const now = this.clock.nowMs();
    if (s && s.refusedUntilMs > now) {
      const retryAfterMs = Math.ceil(s.refusedUntilMs - now);
      return { reason: RefusalReason.Backoff, message: `too many clients from your address were disconnected for misbehaving; try again in ${Math.ceil(retryAfterMs / 1000)} s`, retryAfterMs };
    }
    if (this.sockets >= o.maxSockets) return { reason: RefusalReason.ServerFull, message: `server full (${o.maxSockets} connections)`, retryAfterMs: 5_000 };
    if (s && s.sockets >= o.maxSocketsPerAddress) {
      return { reason: RefusalReason.AddressSockets, message: `too many connections from your address (${o.maxSocketsPerAddress} open)`, retryAfterMs: 5_000 };
    }
    if (s && s.pending >= o.maxPendingPerAddress) {
      return { reason: RefusalReason.AddressPending, message: `too many connections from your address that have not said hello (${o.maxPendingPerAddress})`, retryAfterMs: 1_000 };
    }
    return null;
  }

  /** Counts a socket that was admitted; the ticket reports its hello, kicks and end. */
  open(key: string): ConnectionTicket {
    const s = this.stateOf(key);
    s.sockets++;
    s.pending++;
    this.sockets++;
    let pending = true;
    let open = true;
    return {
      key,
      helloed: () => {
        if (!pending || !open) return;
        pending = false;
        s.pending--;
      },
      kicked: () => this.kick(key),
      closed: () => {
        if (!open) return;
        open = false;
        if (pending) s.pending--;
        pending = false;
        s.sockets--;
        this.sockets--;
        this.forgetIfIdle(key);
      },
    };
  }

  private kick(key: string): void {
    const o = this.options;
    const s = this.stateOf(key);
    const now = this.clock.nowMs();
    s.kicks = this.liveKicks(s) + 1;
    s.lastKickMs = now;
    if (s.kicks >= o.kicksBeforeBackoff) {
      const doublings = Math.min(30, s.kicks - o.kicksBeforeBackoff);
      s.refusedUntilMs = now + Math.min(o.backoffMaxMs, o.backoffBaseMs * 2 ** doublings);
    }
  }

  private liveKicks(s: AddressState): number {
    return this.clock.nowMs() - s.lastKickMs > this.options.kickMemoryMs ? 0 : s.kicks;
  }

  private stateOf(key: string): AddressState {
    let s = this.addresses.get(key);
    if (!s) {
      if (this.addresses.size >= this.options.maxTrackedAddresses) this.evictIdle();
      s = { sockets: 0, pending: 0, kicks: 0, lastKickMs: -Infinity, refusedUntilMs: -Infinity };
      this.addresses.set(key, s);
    }
    return s;
  }

  // Addresses without sockets whose kicks are forgotten and whose refusal has run out carry no information.
  private forgetIfIdle(key: string): void {
    const s = this.addresses.get(key);
    if (s && s.sockets === 0 && this.liveKicks(s) === 0 && s.refusedUntilMs <= this.clock.nowMs()) this.addresses.delete(key);
  }

  /** Forgets addresses that no longer carry anything (no sockets, kicks forgotten, refusal over); call now and then. */
  sweep(): void {
    for (const key of [...this.addresses.keys()]) this.forgetIfIdle(key);
  }

  // At the cap: forget idle addresses, then the oldest ones without open sockets (the map keeps insertion order),
  // down to 90% of the cap so that the scan is not repeated for every new address.
  private evictIdle(): void {
    this.sweep();
    const target = Math.floor(this.options.maxTrackedAddresses * 0.9);
    for (const [key, s] of this.addresses) {
      if (this.addresses.size <= target) break;
      if (s.sockets === 0) this.addresses.delete(key);
    }
  }
}
