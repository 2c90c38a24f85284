// Tests for server/client-address.ts: the socket's address by default, X-Forwarded-For/-Proto only with trustProxy
// (the last hop, malformed entries ignored), IPv4-mapped addresses, and the per-/64 key of IPv6 addresses.
import type { IncomingMessage } from 'node:http';
import { describe, expect, it } from 'vitest';
import { addressKey, clientAddress, describeAddress, normalizeAddress } from '../../server/client-address.ts';

function request(remoteAddress: string, headers: Record<string, string | string[]> = {}, encrypted = false): IncomingMessage {
  return { socket: { remoteAddress, remotePort: 50_000, encrypted }, headers } as unknown as IncomingMessage;
}

describe('client-address', () => {
  it('takes the socket address and ignores forwarding headers unless the proxy is trusted', () => {
    const req = request('::ffff:10.0.0.5', { 'x-forwarded-for': '1.2.3.4', 'x-forwarded-proto': 'https' });
    expect(clientAddress(req, false)).toEqual({ address: '10.0.0.5', port: 50_000, secure: false, forwarded: false });
    expect(clientAddress(request('10.0.0.5', {}, true), false).secure).toBe(true);
  });

  it('with trustProxy reads the last X-Forwarded-For hop and X-Forwarded-Proto', () => {
    const req = request('10.0.0.1', { 'x-forwarded-for': '6.6.6.6, 203.0.113.7', 'x-forwarded-proto': 'http, https' });
    expect(clientAddress(req, true)).toEqual({ address: '203.0.113.7', port: null, secure: true, forwarded: true });
    expect(clientAddress(request('10.0.0.1', { 'x-forwarded-for': '[2001:db8::1]:443' }), true).address).toBe('2001:db8::1');
    expect(clientAddress(request('10.0.0.1', { 'x-forwarded-for': '198.51.100.2:8080' }), true).address).toBe('198.51.100.2');
  });

  it('falls back to the socket address when the forwarded hop is not an IP address', () => {
    const req = request('10.0.0.1', { 'x-forwarded-for': 'evil, not-an-ip' });
    expect(clientAddress(req, true)).toMatchObject({ address: '10.0.0.1', port: 50_000, forwarded: false });
    expect(clientAddress(request('10.0.0.1', { 'x-forwarded-for': 'junk', 'x-forwarded-proto': 'https' }), true)).toEqual({ address: '10.0.0.1', port: 50_000, secure: true, forwarded: true });
    expect(clientAddress(request('10.0.0.1'), true)).toMatchObject({ address: '10.0.0.1', forwarded: false });
  });

  it('keys IPv4 by address and IPv6 by its /64', () => {
    expect(addressKey('127.0.0.2')).toBe('127.0.0.2');
    expect(addressKey('2001:db8:0:12:aaaa::1')).toBe('2001:db8:0:12::/64');
    expect(addressKey('2001:DB8:0:12:ffff:1:2:3')).toBe('2001:db8:0:12::/64');
    expect(addressKey('2001:db8::1')).toBe('2001:db8:0:0::/64');
    expect(addressKey('::1')).toBe('0:0:0:0::/64');
    expect(addressKey('64:ff9b::192.0.2.33')).toBe('64:ff9b:0:0::/64');
    expect(normalizeAddress('::ffff:127.0.0.1')).toBe('127.0.0.1');
  });

  it('describes an address for logs', () => {
    expect(describeAddress({ address: '::1', port: 8, secure: false, forwarded: false })).toBe('[::1]:8');
    expect(describeAddress({ address: '1.2.3.4', port: null, secure: true, forwarded: true })).toBe('1.2.3.4 (forwarded)');
  });
});
