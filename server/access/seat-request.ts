// The body of `POST /api/rooms/:id/seats` (`{}` or `{"ttlSeconds": n}`, or empty) and the reservation as the route
// answers it. Parsing only: the route in http-server.ts reserves the seat through the HttpApi.
import { MAX_SEAT_TTL_MS } from './seat-tokens.ts';

/** A checked seat request. */
export interface SeatRequest {
  /** Lifetime of the token in seconds (default: the server's --seat-ttl). */
  ttlSeconds?: number;
}

/** A reserved seat as the route answers it. */
export interface SeatAnswer {
  /** What the player passes as its seat (`connect(url, {seat})`, or `hello.seatToken`). */
  token: string;
  roomId: string;
  seatId: string;
  /** ISO 8601 time after which the token is refused. */
  expiresAt: string;
}

/** Parses the request body; throws an Error with `status: 400` naming the problem. */
export function parseSeatRequest(text: string): SeatRequest {
  if (text.trim() === '') return {};
  const fail = (message: string): never => {
    throw Object.assign(new Error(message), { status: 400, code: 'bad-request' });
  };
  let v: unknown;
  try {
    v = JSON.parse(text);
  } catch {
    return fail('body must be empty or JSON: {"ttlSeconds"?: seconds}');
  }
  if (v === null || typeof v !== 'object' || Array.isArray(v)) return fail('body must be a JSON object');
  const out: SeatRequest = {};
  for (const [key, value] of Object.entries(v as Record<string, unknown>)) {
    if (key !== 'ttlSeconds') return fail(`unknown field ${JSON.stringify(key.slice(0, 40))} (known: ttlSeconds)`);
    const max = MAX_SEAT_TTL_MS / 1000;
    if (typeof value !== 'number' || !Number.isInteger(value) || value < 1 || value > max) return fail(`"ttlSeconds" must be a whole number of seconds in [1, ${max}]`);
    out.ttlSeconds = value;
  }
  return out;
}
