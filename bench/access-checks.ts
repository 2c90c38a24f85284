// What each access check costs, per request, upgrade or hello: the Origin check, the admin token comparison, seat
// token issue/verify/redeem, resume token issue + claim, and hello decoding with and without tokens.
// Usage: node_modules/.bin/node bench/access-checks.ts [iterations]   (prints one line per check, median of 5 runs)
import type { IncomingMessage } from 'node:http';
import { AdminAuth } from '../server/access/admin-auth.ts';
import { createHttpGuard } from '../server/access/http-guard.ts';
import { originFacts, parseAllowedOrigins } from '../server/access/origin-policy.ts';
import { ResumeTokens } from '../server/access/resume-tokens.ts';
import { SeatTokens } from '../server/access/seat-tokens.ts';
import { ManualClock } from '../shared/clock.ts';
import type { Room } from '../server/room.ts';
import { encodeClientMessage, PROTOCOL_VERSION } from '../shared/protocol/index.ts';
import { decodeClientMessage } from '../shared/protocol/validation.ts';

const iterations = Number(process.argv[2] ?? 20_000);
const TOKEN = 'bench-admin-token-0123456789abcdef';

function req(headers: Record<string, string>): IncomingMessage {
  return { headers: { host: '192.168.1.5:8080', ...headers }, socket: {} } as unknown as IncomingMessage;
}

/** Median over 5 runs of the mean time per call, in microseconds. */
function measure(fn: (i: number) => unknown): number {
  for (let i = 0; i < Math.min(2000, iterations); i++) fn(i); // warm up
  const runs: number[] = [];
  for (let r = 0; r < 5; r++) {
    const t0 = process.hrtime.bigint();
    for (let i = 0; i < iterations; i++) fn(i);
    runs.push(Number(process.hrtime.bigint() - t0) / 1000 / iterations);
  }
  return runs.sort((a, b) => a - b)[2];
}

const origins = parseAllowedOrigins(undefined);
const listed = parseAllowedOrigins('https://game.example,https://play.example');
const admin = new AdminAuth(TOKEN);
const guard = createHttpGuard({ origins, admin });
const seats = new SeatTokens({ secret: 'bench-join-secret-0123456789' });
const seat = seats.issue('default', 3_600_000);
const room = { id: 'default', closed: false, hasPlayer: () => true, onClose: () => () => undefined, detach: () => true, leave: () => undefined } as unknown as Room;
const resume = new ResumeTokens({ clock: new ManualClock(), graceMs: 30_000 });
let token = resume.issue(room, 1, { replaced: () => undefined });
const plainHello = encodeClientMessage({ type: 'hello', version: PROTOCOL_VERSION, name: 'Ada', room: null });
const tokenHello = encodeClientMessage({ type: 'hello', version: PROTOCOL_VERSION, name: 'Ada', room: null, seatToken: seat.token, resumeToken: token });

const rows: Array<[string, number]> = [
  ['origin check: no Origin (program)', measure(() => origins.check(originFacts(req({}))))],
  ['origin check: loopback page', measure(() => origins.check(originFacts(req({ origin: 'http://localhost:5173' }))))],
  ['origin check: self (page from this IP)', measure(() => origins.check(originFacts(req({ origin: 'http://192.168.1.5:8080' }))))],
  ['origin check: listed origin', measure(() => listed.check(originFacts(req({ origin: 'https://play.example' }))))],
  ['origin check: refused (builds the 403)', measure(() => origins.check(originFacts(req({ origin: 'https://evil.example' }))))],
  ['admin token: right', measure(() => admin.check(`Bearer ${TOKEN}`))],
  ['admin token: wrong', measure(() => admin.check('Bearer not-the-admin-token-000000'))],
  ['HTTP guard: POST /api/rooms, no Origin, token', measure(() => guard(req({ authorization: `Bearer ${TOKEN}` }), 'POST', '/api/rooms'))],
  ['HTTP guard: GET /api/rooms (nothing to check)', measure(() => guard(req({}), 'GET', '/api/rooms'))],
  ['seat: issue', measure(() => seats.issue('default'))],
  ['seat: verify', measure(() => seats.verify(seat.token, null))],
  [
    'seat: redeem (verify + mark used), minus issue',
    measure(() => {
      const r = seats.redeem(seat.token, null);
      if (r.ok) seats.release(r.seatId); // keeps the used-seat table small: this measures one redemption
    }),
  ],
  [
    'resume: claim + issue the next token',
    measure(() => {
      resume.claim(token, null);
      token = resume.issue(room, 1, { replaced: () => undefined });
    }),
  ],
  ['decode hello without tokens', measure(() => decodeClientMessage(plainHello))],
  ['decode hello with seat + resume tokens', measure(() => decodeClientMessage(tokenHello))],
];
console.log(`access checks, ${iterations} calls per run, median of 5 runs (Node ${process.version})`);
for (const [name, us] of rows) console.log(`${name.padEnd(48)} ${us.toFixed(2).padStart(7)} µs`);
