// Tests for server/access/http-guard.ts: which routes need the admin token, the origin check on mutating requests
// only, and the order (origin before token).
import type { IncomingMessage } from 'node:http';
import { describe, expect, it } from 'vitest';
import { AdminAuth } from '../../../server/access/admin-auth.ts';
import { createHttpGuard, isAdminRoute } from '../../../server/access/http-guard.ts';
import { parseAllowedOrigins } from '../../../server/access/origin-policy.ts';
import type { Refusal } from '../../../server/access/refusal.ts';

const TOKEN = 'guard-admin-token-for-tests';

function req(headers: Record<string, string>): IncomingMessage {
  return { headers: { host: '127.0.0.1:8080', ...headers }, socket: {} } as unknown as IncomingMessage;
}

describe('http-guard', () => {
  it('treats /metrics and every mutating /api/ request as an operator route', () => {
    expect(isAdminRoute('GET', '/metrics')).toBe(true);
    expect(isAdminRoute('POST', '/api/rooms')).toBe(true);
    expect(isAdminRoute('DELETE', '/api/rooms/a')).toBe(true);
    expect(isAdminRoute('POST', '/api/rooms/a/seats')).toBe(true);
    expect(isAdminRoute('GET', '/api/rooms')).toBe(false);
    expect(isAdminRoute('GET', '/healthz')).toBe(false);
    expect(isAdminRoute('GET', '/')).toBe(false);
  });

  it('checks the origin of mutating requests first, then the token; reads stay open', () => {
    const refused: Refusal[] = [];
    const guard = createHttpGuard({ origins: parseAllowedOrigins(undefined), admin: new AdminAuth(TOKEN), onRefused: (r) => refused.push(r) });
    expect(guard(req({ origin: 'https://evil.example' }), 'GET', '/api/rooms')).toBeNull();
    expect(guard(req({ origin: 'https://evil.example', authorization: `Bearer ${TOKEN}` }), 'POST', '/api/rooms')).toMatchObject({ status: 403, code: 'origin-not-allowed' });
    expect(guard(req({}), 'POST', '/api/rooms')).toMatchObject({ status: 401 });
    expect(guard(req({ authorization: `Bearer ${TOKEN}` }), 'POST', '/api/rooms')).toBeNull();
    expect(guard(req({ origin: 'http://127.0.0.1:8080', authorization: `Bearer ${TOKEN}` }), 'DELETE', '/api/rooms/x')).toBeNull();
    expect(guard(req({}), 'GET', '/metrics')).toMatchObject({ status: 401 });
    expect(guard(req({ 'sec-fetch-site': 'cross-site', authorization: `Bearer ${TOKEN}` }), 'POST', '/api/rooms')).toMatchObject({ code: 'cross-site-request' });
    expect(refused.map((r) => r.code)).toEqual(['origin-not-allowed', 'admin-token-required', 'admin-token-required', 'cross-site-request']);
  });

  it('leaves operator routes to the origin check alone when no admin token is set', () => {
    const guard = createHttpGuard({ origins: parseAllowedOrigins(undefined), admin: null });
    expect(guard(req({}), 'POST', '/api/rooms')).toBeNull();
    expect(guard(req({}), 'GET', '/metrics')).toBeNull();
    expect(guard(req({ origin: 'https://evil.example' }), 'POST', '/api/rooms')).toMatchObject({ status: 403 });
  });
});
