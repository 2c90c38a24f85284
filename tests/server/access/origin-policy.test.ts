// Tests for server/access/origin-policy.ts: the default list (self, loopback), explicit origins, `*`, requests
// without an Origin (programs), cross-site browser requests without one, and parse errors.
import { describe, expect, it } from 'vitest';
import { normalizeOrigin, parseAllowedOrigins, type OriginFacts } from '../../../server/access/origin-policy.ts';

const facts = (origin: string | undefined, host: string | undefined, extra: Partial<OriginFacts> = {}): OriginFacts => ({ origin, host, fetchSite: undefined, secure: false, ...extra });

describe('origin-policy', () => {
  it('allows by default pages on loopback (any port) and pages served from this very IP address', () => {
    const p = parseAllowedOrigins(undefined);
    expect(p.entries).toEqual(['self', 'loopback']);
    for (const o of ['http://localhost:8080', 'http://localhost:3000', 'https://game.localhost', 'http://127.0.0.1:5173', 'http://127.9.9.9', 'http://[::1]:8080']) {
      expect(p.check(facts(o, '192.168.1.5:8080')), o).toBeNull();
    }
    expect(p.check(facts('http://192.168.1.5:8080', '192.168.1.5:8080'))).toBeNull();
    expect(p.check(facts('http://[fe80::1]:8080', '[fe80::1]:8080'))).toBeNull();
    expect(p.check(facts('http://192.168.1.5', '192.168.1.5:80'))).toBeNull(); // default port written out by the client
  });

  it('refuses other sites, another port of this address, and a name served over plain HTTP (DNS rebinding)', () => {
    const p = parseAllowedOrigins(undefined);
    const refused = [
      facts('https://evil.example', '127.0.0.1:8080'),
      facts('http://192.168.1.5:9999', '192.168.1.5:8080'),
      facts('http://192.168.1.6:8080', '192.168.1.5:8080'),
      facts('http://evil.example:8080', 'evil.example:8080'), // a rebound name looks same-origin; it is refused
      facts('null', '127.0.0.1:8080'),
      facts('http://192.168.1.5:8080', undefined),
      facts('http://192.168.1.5:8080', '192.168.1.5:8080/x'),
    ];
    for (const f of refused) expect(p.check(f), JSON.stringify(f)).toMatchObject({ status: 403, code: 'origin-not-allowed' });
    expect(p.check(facts('https://evil.example', '127.0.0.1:8080'))?.message).toMatch(/origin "https:\/\/evil.example" is not allowed \(allowed: self,loopback\); start the server with --allowed-origins/);
  });

  it('counts a name as self only over TLS, where a rebound name would fail the certificate check', () => {
    const p = parseAllowedOrigins('self');
    expect(p.check(facts('https://game.example', 'game.example', { secure: true }))).toBeNull();
    expect(p.check(facts('https://game.example:8443', 'game.example:8443', { secure: true }))).toBeNull();
    expect(p.check(facts('https://game.example', 'game.example', { secure: false }))).not.toBeNull();
    expect(p.check(facts('http://localhost:3000', 'localhost:8080'))).not.toBeNull(); // loopback not listed
  });

  it('lets requests without an Origin through, unless a browser marks them cross-site or same-site', () => {
    const p = parseAllowedOrigins(undefined);
    expect(p.check(facts(undefined, '127.0.0.1:8080'))).toBeNull();
    expect(p.check(facts(undefined, '127.0.0.1:8080', { fetchSite: 'same-origin' }))).toBeNull();
    expect(p.check(facts(undefined, '127.0.0.1:8080', { fetchSite: 'none' }))).toBeNull();
    expect(p.check(facts(undefined, '127.0.0.1:8080', { fetchSite: 'cross-site' }))).toMatchObject({ status: 403, code: 'cross-site-request' });
    expect(p.check(facts(undefined, '127.0.0.1:8080', { fetchSite: 'same-site' }))).toMatchObject({ code: 'cross-site-request' });
  });

  it('matches listed origins exactly and turns the check off with *', () => {
    const p = parseAllowedOrigins('https://game.example, https://play.example:8443');
    expect(p.check(facts('https://game.example', 'api.example'))).toBeNull();
    expect(p.check(facts('https://play.example:8443', 'api.example'))).toBeNull();
    expect(p.check(facts('http://game.example', 'api.example'))).not.toBeNull();
    expect(p.check(facts('https://sub.game.example', 'api.example'))).not.toBeNull();
    expect(p.check(facts('http://localhost:3000', 'localhost:8080'))).not.toBeNull();
    const any = parseAllowedOrigins(['*']);
    expect(any.check(facts('https://anything.example', 'x'))).toBeNull();
    expect(any.check(facts('null', 'x'))).toBeNull();
  });

  it('normalizes listed origins the way browsers send them and refuses entries that are not origins', () => {
    expect(normalizeOrigin('HTTPS://Game.Example:443/')).toBe('https://game.example');
    expect(parseAllowedOrigins('HTTPS://Game.Example:443').check(facts('https://game.example', 'x'))).toBeNull();
    for (const bad of ['game.example', 'ftp://game.example', 'https://game.example/path', 'https://user@game.example', 'https://game.example?q=1']) {
      expect(() => parseAllowedOrigins(bad), bad).toThrow(/is not an origin/);
    }
    expect(() => parseAllowedOrigins(' , ')).toThrow(/at least one entry/);
  });
});
