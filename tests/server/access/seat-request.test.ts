// Tests for server/access/seat-request.ts: an empty body, a lifetime, and refusals naming the field.
import { describe, expect, it } from 'vitest';
import { parseSeatRequest } from '../../../server/access/seat-request.ts';

describe('seat-request', () => {
  it('reads an empty body, an empty object and a lifetime in seconds', () => {
    expect(parseSeatRequest('')).toEqual({});
    expect(parseSeatRequest(' {} ')).toEqual({});
    expect(parseSeatRequest('{"ttlSeconds": 120}')).toEqual({ ttlSeconds: 120 });
  });

  it('refuses bad JSON, unknown fields and lifetimes out of range with status 400', () => {
    const cases: Array<[string, RegExp]> = [
      ['nope', /must be empty or JSON/],
      ['[1]', /must be a JSON object/],
      ['{"ttl": 5}', /unknown field "ttl" \(known: ttlSeconds\)/],
      ['{"ttlSeconds": 0}', /whole number of seconds in \[1, 3600\]/],
      ['{"ttlSeconds": 1.5}', /whole number/],
      ['{"ttlSeconds": "60"}', /whole number/],
      ['{"ttlSeconds": 3601}', /\[1, 3600\]/],
    ];
    for (const [body, message] of cases) {
      expect(() => parseSeatRequest(body), body).toThrow(message);
      try {
        parseSeatRequest(body);
      } catch (e) {
        expect((e as { status?: number }).status).toBe(400);
      }
    }
  });
});
