// Tests for server/access/access-setup.ts: options are checked before anything starts, the summary names what is in
// force without secrets, and a server reachable from other machines without an admin token gets a warning.
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

  it('warns when operator routes are open on an address other machines can reach', () => {
    expect(openAdminWarning('0.0.0.0', createServerAccess({}, metrics()))).toMatch(/without --admin-token: anyone who can reach the port/);
    expect(openAdminWarning('127.0.0.1', createServerAccess({}, metrics()))).toBeNull();
    expect(openAdminWarning('0.0.0.0', createServerAccess({ adminToken: TOKEN }, metrics()))).toBeNull();
  });
});
