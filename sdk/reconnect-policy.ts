// When and how soon the client reconnects: exponential backoff with jitter, a cap on attempts, and which endings
// are final (a shutdown, a kick, a full room or server, a refused version or seat, a missing room, a takeover) versus
// worth retrying (a dropped link, a timeout).
import { ErrorCode, RECONNECTABLE_BYE_REASONS } from '../shared/protocol/opcodes.ts';

/** Reconnect settings. */
export interface ReconnectOptions {
  /** Whether to reconnect after an unexpected close. Default true. */
  enabled?: boolean;
  /** Attempts before giving up (counted since the last successful welcome). Default 10. */
  maxAttempts?: number;
  /** Delay before the first attempt (ms). Default 250. */
  baseDelayMs?: number;
  /** Longest delay between attempts (ms). Default 10000. */
  maxDelayMs?: number;
}

/** Resolved settings. */
export interface ReconnectPolicy {
  enabled: boolean;
  maxAttempts: number;
  baseDelayMs: number;
  maxDelayMs: number;
}

/** Fills defaults and checks the values. */
export function reconnectPolicy(opts: ReconnectOptions | false | undefined): ReconnectPolicy {
  if (opts === false) return { enabled: false, maxAttempts: 0, baseDelayMs: 250, maxDelayMs: 10000 };
  const p = { enabled: opts?.enabled ?? true, maxAttempts: opts?.maxAttempts ?? 10, baseDelayMs: opts?.baseDelayMs ?? 250, maxDelayMs: opts?.maxDelayMs ?? 10000 };
  if (!Number.isInteger(p.maxAttempts) || p.maxAttempts < 0) throw new Error(`reconnect.maxAttempts must be an integer ≥ 0, got ${p.maxAttempts}`);
  if (!(p.baseDelayMs >= 0) || !(p.maxDelayMs >= p.baseDelayMs)) throw new Error('reconnect: need 0 ≤ baseDelayMs ≤ maxDelayMs');
  return p;
}

/** Delay before attempt n (1-based): base·2^(n−1), capped, scaled by a jitter factor in [0.75, 1.25). */
export function backoffDelayMs(policy: ReconnectPolicy, attempt: number, random: () => number): number {
  let d = policy.baseDelayMs;
  for (let i = 1; i < attempt && d < policy.maxDelayMs; i++) d *= 2;
  d = Math.min(d, policy.maxDelayMs);
  return Math.round(d * (0.75 + 0.5 * random()));
}

/** Error codes that make retrying pointless. */
const FINAL_ERRORS: ReadonlySet<string> = new Set<string>([
  ErrorCode.VersionMismatch,
  ErrorCode.RoomNotFound,
  ErrorCode.BadMessage,
  ErrorCode.Malformed,
  ErrorCode.SeatRequired,
  ErrorCode.SeatRefused,
  ErrorCode.RoomFull,
  ErrorCode.ServerFull,
]);

/** Whether an ending allows a reconnect: no bye or a timeout bye, and no final error before the welcome. */
export function isRetryable(bye: string | null, errorBeforeWelcome: string | null): boolean {
  if (bye !== null) return RECONNECTABLE_BYE_REASONS.has(bye);
  if (errorBeforeWelcome !== null) return !FINAL_ERRORS.has(errorBeforeWelcome);
  return true;
}
