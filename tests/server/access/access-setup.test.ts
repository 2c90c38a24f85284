// Tests for server/access/access-setup.ts: options are checked before anything starts, the summary names what is in
// force without secrets, refused origins are counted and logged once each, and a server reachable from other machines
// without an admin token gets a warning.
import type { IncomingMessage } from 'node:http';
import { pino } from 'pino';
import { describe, expect, it } from 'vitest';
import { createServerAccess, openAdminWarning } from '../../../server/access/access-setup.ts';
import { createMetrics } from '../../../server/metrics.ts';

const TOKEN = 'setup-admin-token-for-tests';
const metrics = () => createMetrics({ processMetrics: false });

describe('access-setup', () => {
  it('refuses --require-seat without an admin token, and bad origins, tokens and secrets', () => {
    expect(() => createServerAccess({ requireSeat: true }, metrics())).toThrow(/--require-seat needs --admin-token/);
    expect(() => createServerAccess({ allowedOrigins: 'nope' }, metrics())).toThrow(/"nope" is not an origin/);
    expect(() => createServerAccess({ adminToken: 'short' }, metrics())).toThrow(/at least 16/);
    expect(() => createServerAccess({ joinSecret: 'short' }, metrics())).toThrow(/at least 16/);
  });

  it('summarizes what is in force without secrets, with a random join secret when none is given', () => {
    const a = createServerAccess({ adminToken: TOKEN, requireSeat: true, seatTtlMs: 30_000 }, metrics());
    expect(a.summary).toEqual({ allowedOrigins: 'self,loopback', adminToken: true, joinSecret: 'random per process', requireSeat: true, seatTtlSeconds: 30 });
    expect(JSON.stringify(a.summary)).not.toContain(TOKEN);
    const b = createServerAccess({ joinSecret: 'a-join-secret-of-length', allowedOrigins: ['https://game.example'] }, metrics());
    expect(b.summary).toMatchObject({ allowedOrigins: 'https://game.example', adminToken: false, joinSecret: 'given' });
    // Two processes with the same secret accept each other's seats; a random secret is this process's alone.
    const c = createServerAccess({ joinSecret: 'a-join-secret-of-length' }, metrics());
    expect(c.seats.verify(b.seats.issue('default').token, null).ok).toBe(true);
    expect(a.seats.verify(b.seats.issue('default').token, null).ok).toBe(false);
  });

  it('counts refusals and logs each refused origin once, so an operator learns what to list', () => {
    const m = metrics();
    const lines: Array<Record<string, unknown>> = [];
    const logger = pino({ level: 'warn' }, { write: (line: string) => void lines.push(JSON.parse(line) as Record<string, unknown>) });
    const a = createServerAccess({}, m, logger);
    const upgrade = (origin: string) => ({ headers: { origin, host: '127.0.0.1:8080' }, socket: {} }) as unknown as IncomingMessage;
    expect(a.checkUpgrade(upgrade('http://mybox.lan:8080'))).toMatchObject({ status: 403 });
    expect(a.checkUpgrade(upgrade('http://mybox.lan:8080'))).toMatchObject({ status: 403 });
    expect(a.authorize(upgrade('https://evil.example'), 'POST', '/api/rooms')).toMatchObject({ status: 403 });
    expect(a.checkUpgrade(upgrade('http://localhost:3000'))).toBeNull();
    expect(lines.map((l) => l.origin)).toEqual(['http://mybox.lan:8080', 'https://evil.example']);
    expect(lines[0]).toMatchObject({ allowed: 'self,loopback', msg: expect.stringMatching(/--allowed-origins/) });
  });

  it('warns when operator routes are open on an address other machines can reach', () => {
    expect(openAdminWarning('0.0.0.0', createServerAccess({}, metrics()))).toMatch(/without --admin-token: anyone who can reach the port/);
    expect(openAdminWarning('127.0.0.1', createServerAccess({}, metrics()))).toBeNull();
    expect(openAdminWarning('0.0.0.0', createServerAccess({ adminToken: TOKEN }, metrics()))).toBeNull();
  });
});
