// Resume tokens and the reconnect grace window: every welcome carries a fresh unguessable token bound to (room,
// player); a link that drops without a bye leaves its player held in the room for the grace window, and a new
// connection that shows the token within it takes the same player back. Tokens are single use; spent ones are
// remembered (bounded) so a refusal can say why.
import { createHash, randomBytes } from 'node:crypto';
import type { Clock, TimerHandle } from '../../shared/clock.ts';
import type { Logger } from '../logger.ts';
import type { HostedRoom as Room } from '../hosted-room.ts';

/** Default grace window. */
export const DEFAULT_RESUME_GRACE_MS = 30_000;
/** Spent tokens remembered for a precise refusal reason; older ones are just "unknown". */
const REMEMBER_SPENT = 4096;

/** The connection that currently owns a player. */
export interface ResumeHolder {
  /** Another connection took the player over: end this one without leaving the room. */
  replaced(): void;
}

/** A claimed player, or why the token is refused. */
export type ResumeClaim = { ok: true; room: Room; playerId: number } | { ok: false; reason: string };

interface Entry {
  key: string;
  room: Room;
  playerId: number;
  holder: ResumeHolder | null;
  timer: TimerHandle | null;
}

/** Options of ResumeTokens. */
export interface ResumeTokensOptions {
  clock: Clock;
  /** How long a dropped player is held. */
  graceMs: number;
  logger?: Logger;
  /** Hears every token issued, by its key (SHA-256, never the token): a recording keeps them for --resume. */
  onIssue?: (room: Room, playerId: number, key: string) => void;
}

/** Tokens by their SHA-256, so a lookup's timing says nothing about any token's text. */
function keyOf(token: string): string {
  return createHash('sha256').update(token, 'utf8').digest('base64url');
}

/** Issues, holds and redeems resume tokens for every room of a server. */
export class ResumeTokens {
  readonly graceMs: number;
  private readonly clock: Clock;
  private readonly logger: Logger | null;
  private readonly onIssue: ResumeTokensOptions['onIssue'];
  private readonly byKey = new Map<string, Entry>();
  private readonly byRoom = new Map<Room, Map<number, Entry>>();
  private readonly spent = new Map<string, string>();

  constructor(opts: ResumeTokensOptions) {
    if (!Number.isInteger(opts.graceMs) || opts.graceMs <= 0) throw new Error(`the resume grace window must be a positive whole number of ms, got ${opts.graceMs}`);
    this.clock = opts.clock;
    this.graceMs = opts.graceMs;
    this.logger = opts.logger ?? null;
    this.onIssue = opts.onIssue;
  }

  /** Players held now (link down, character kept). */
  get heldCount(): number {
    let n = 0;
    for (const e of this.byKey.values()) if (e.timer !== null) n++;
    return n;
  }

  /** Players with a live token (held or connected). */
  get size(): number {
    return this.byKey.size;
  }

  /** A new token for a player now owned by `holder`; any earlier token of that player is spent. */
  issue(room: Room, playerId: number, holder: ResumeHolder): string {
    const previous = this.byRoom.get(room)?.get(playerId);
    if (previous) this.forget(previous, 'the resume token was replaced by a newer one');
    const token = randomBytes(32).toString('base64url');
    const entry = this.track({ key: keyOf(token), room, playerId, holder, timer: null });
    this.onIssue?.(room, playerId, entry.key);
    return token;
  }

  /**
   * A resumed room's player (Room.restorePlayers) whose token was issued before the restart, by its stored key: held
   * for the grace window from now, then it leaves, as after a dropped link.
   */
  adopt(room: Room, playerId: number, key: string): void {
    if (this.byKey.has(key) || room.closed || !room.hasPlayer(playerId)) return;
    this.startGrace(this.track({ key, room, playerId, holder: null, timer: null }));
  }

  // Indexes an entry by key and by room (a room's first entry also arranges for its tokens to go when it closes).
  private track(entry: Entry): Entry {
    this.byKey.set(entry.key, entry);
    let players = this.byRoom.get(entry.room);
    if (!players) {
      players = new Map();
      this.byRoom.set(entry.room, players);
      const room = entry.room;
      room.onClose(() => this.dropRoom(room));
    }
    players.set(entry.playerId, entry);
    return entry;
  }

  /**
   * The player's link dropped without a bye: the room holds its character (Room.detach) and the player leaves when
   * the grace window ends. False when the player has no token (the caller should let it leave now).
   */
  hold(room: Room, playerId: number): boolean {
    const entry = this.byRoom.get(room)?.get(playerId);
    if (!entry || room.closed || !room.detach(playerId)) return false;
    entry.holder = null;
    this.startGrace(entry);
    return true;
  }

  private startGrace(entry: Entry): void {
    const { room, playerId } = entry;
    entry.timer = this.clock.setTimer(this.graceMs, () => {
      entry.timer = null;
      this.forget(entry, `the resume token expired: the ${Math.round(this.graceMs / 1000)} s grace window ended`);
      this.logger?.info({ room: room.id, playerId }, 'held player left: the reconnect grace window ended');
      room.leave(playerId);
    });
  }

  /** The player left for good (bye, kick, removal): its token is spent. */
  release(room: Room, playerId: number, reason = 'the player left the room'): void {
    const entry = this.byRoom.get(room)?.get(playerId);
    if (entry) this.forget(entry, `the resume token is void: ${reason}`);
  }

  /**
   * Takes a player back with its token: the token is spent, the grace timer stops, and a connection still holding
   * the player is told it was replaced. `room` is the room the hello asked for (null: the token's own room). The
   * caller then reattaches the player to the new connection and issues it a new token.
   */
  claim(token: string, room: string | null): ResumeClaim {
    const key = keyOf(token);
    const entry = this.byKey.get(key);
    if (!entry) return { ok: false, reason: this.spent.get(key) ?? 'the resume token is unknown to this server' };
    if (room !== null && room !== entry.room.id) return { ok: false, reason: `the resume token is for room "${entry.room.id}", not "${room}"` };
    if (entry.room.closed || !entry.room.hasPlayer(entry.playerId)) {
      this.forget(entry, 'the resume token is void: the player is no longer in the room');
      return { ok: false, reason: 'the player is no longer in the room' };
    }
    const holder = entry.holder;
    this.forget(entry, 'the resume token was already used');
    holder?.replaced();
    return { ok: true, room: entry.room, playerId: entry.playerId };
  }

  private forget(entry: Entry, why: string): void {
    if (this.byKey.get(entry.key) !== entry) return;
    this.byKey.delete(entry.key);
    const players = this.byRoom.get(entry.room);
    if (players?.get(entry.playerId) === entry) players.delete(entry.playerId);
    if (entry.timer !== null) this.clock.clearTimer(entry.timer);
    entry.timer = null;
    entry.holder = null;
    this.spent.set(entry.key, why);
    if (this.spent.size > REMEMBER_SPENT) this.spent.delete(this.spent.keys().next().value as string);
  }

  private dropRoom(room: Room): void {
    const players = this.byRoom.get(room);
    if (!players) return;
    for (const entry of [...players.values()]) this.forget(entry, 'the resume token is void: its room has closed');
    this.byRoom.delete(room);
  }
}
