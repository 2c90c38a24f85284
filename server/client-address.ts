// Who a request comes from: the socket's remote address, or — only with --trust-proxy — the hop the reverse proxy
// appended to X-Forwarded-For, plus whether the client used TLS (X-Forwarded-Proto). The connection policy and the
// logs both read it from here; nothing else parses those headers.
import type { IncomingMessage } from 'node:http';
import { isIP } from 'node:net';
import type { TLSSocket } from 'node:tls';

/** Where a request comes from. */
export interface ClientAddress {
  /** The client's IP address; an IPv4-mapped IPv6 address is written as IPv4. */
  address: string;
  /** The client's port, when the server saw the client's own socket (null behind a proxy). */
  port: number | null;
  /** Whether the client spoke TLS: the socket itself, or X-Forwarded-Proto https with trustProxy. */
  secure: boolean;
  /** Whether address and secure were read from X-Forwarded-* headers. */
  forwarded: boolean;
}

/** Strips IPv4-mapped IPv6 (`::ffff:1.2.3.4`) down to the IPv4 address; other addresses are returned as given. */
export function normalizeAddress(address: string): string {
  const mapped = /^::ffff:(\d{1,3}(?:\.\d{1,3}){3})$/i.exec(address);
  return mapped ? mapped[1] : address;
}

/** The last comma-separated entry of a header (repeated headers are joined with commas by Node). */
function lastEntry(value: string | string[] | undefined): string | null {
  if (value === undefined) return null;
  const joined = Array.isArray(value) ? value.join(',') : value;
  const entries = joined.split(',');
  const last = entries[entries.length - 1].trim();
  return last === '' ? null : last;
}

/** An X-Forwarded-For entry as a bare IP (brackets and a port stripped), or null when it is not one. */
function forwardedIp(entry: string): string | null {
  let ip = entry;
  const bracketed = /^\[([^\]]+)\](?::\d+)?$/.exec(ip);
  if (bracketed) ip = bracketed[1];
  else if (/^\d{1,3}(?:\.\d{1,3}){3}:\d+$/.test(ip)) ip = ip.slice(0, ip.lastIndexOf(':'));
  return isIP(ip) === 0 ? null : normalizeAddress(ip);
}

/**
 * The client behind `req`. Without `trustProxy` the headers are ignored: anyone can send them. With it, the server
 * must only be reachable through one reverse proxy, whose appended X-Forwarded-For entry (the last) is the client; a
 * missing or malformed entry falls back to the socket's address (the proxy's).
 */
export function clientAddress(req: IncomingMessage, trustProxy: boolean): ClientAddress {
  const socket = req.socket;
  const own: ClientAddress = {
    address: normalizeAddress(socket.remoteAddress ?? 'unknown'),
    port: socket.remotePort ?? null,
    secure: (socket as Partial<TLSSocket>).encrypted === true,
    forwarded: false,
  };
  if (!trustProxy) return own;
  const hop = lastEntry(req.headers['x-forwarded-for']);
  const ip = hop === null ? null : forwardedIp(hop);
  const proto = lastEntry(req.headers['x-forwarded-proto'])?.toLowerCase();
  if (ip === null && proto === undefined) return own;
  return {
    address: ip ?? own.address,
    port: ip === null ? own.port : null,
    secure: proto === undefined ? own.secure : proto === 'https' || proto === 'wss',
    forwarded: true,
  };
}

/**
 * The key the connection policy counts an address under: IPv4 addresses as they are, IPv6 addresses by their /64
 * (one host usually holds a whole /64, so per-address limits on full IPv6 addresses would not limit anyone).
 */
export function addressKey(address: string): string {
  if (isIP(address) !== 6) return address;
  const [head, tail] = address.split('::');
  const headGroups = head === '' ? [] : head.split(':');
  const tailGroups = tail === undefined || tail === '' ? [] : tail.split(':').flatMap((g) => (g.includes('.') ? ['0', '0'] : [g])); // a dotted IPv4 tail is two groups
  const groups = tail === undefined ? headGroups : [...headGroups, ...new Array<string>(8 - headGroups.length - tailGroups.length).fill('0'), ...tailGroups];
  return `${groups
    .slice(0, 4)
    .map((g) => (g.replace(/^0+/, '') || '0').toLowerCase())
    .join(':')}::/64`;
}

/** `address:port` (IPv6 in brackets) for logs. */
export function describeAddress(c: ClientAddress): string {
  const host = c.address.includes(':') ? `[${c.address}]` : c.address;
  return c.port === null ? `${host} (forwarded)` : `${host}:${c.port}`;
}
