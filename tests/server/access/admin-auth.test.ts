// Tests for server/access/admin-auth.ts: a missing or non-bearer Authorization is 401 with a challenge, a wrong token
// 403, the right one passes; unusable tokens are refused up front.
import { describe, expect, it } from 'vitest';
import { AdminAuth, checkAdminTokenText } from '../../../server/access/admin-auth.ts';

const TOKEN = 'c0ffee-admin-token-for-tests';

describe('admin-auth', () => {
  it('asks for the token with 401 and a Bearer challenge when none is sent', () => {
    const auth = new AdminAuth(TOKEN);
    for (const header of [undefined, '', 'Basic dXNlcjpwYXNz', `Token ${TOKEN}`, 'Bearer']) {
      expect(auth.check(header), String(header)).toEqual({
        status: 401,
        code: 'admin-token-required',
        message: expect.stringMatching(/Authorization: Bearer/),
        headers: { 'WWW-Authenticate': 'Bearer realm="taos-physics"' },
      });
    }
  });

  it('refuses a wrong token with 403 and accepts the right one in any scheme case', () => {
    const auth = new AdminAuth(TOKEN);
    expect(auth.check(`Bearer ${TOKEN}x`)).toMatchObject({ status: 403, code: 'admin-token-wrong' });
    expect(auth.check(`Bearer ${TOKEN.slice(0, -1)}`)).toMatchObject({ status: 403 });
    expect(auth.check('Bearer short')).toMatchObject({ status: 403 });
    expect(auth.check(`Bearer ${TOKEN}`)).toBeNull();
    expect(auth.check(`bearer ${TOKEN}`)).toBeNull();
    expect(auth.check(`BEARER  ${TOKEN} `)).toBeNull();
  });

  it('refuses tokens that are too short or cannot travel in a header', () => {
    expect(() => new AdminAuth('short')).toThrow(/at least 16 characters/);
    expect(() => checkAdminTokenText('has a space in it, long enough')).toThrow(/printable ASCII without spaces/);
    expect(() => checkAdminTokenText('ünïcödé-token-long-enough', 'TAOS_ADMIN_TOKEN')).toThrow(/^TAOS_ADMIN_TOKEN must be printable ASCII/);
  });
});
