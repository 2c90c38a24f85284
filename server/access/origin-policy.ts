// Which browser pages may open a game WebSocket or make a mutating HTTP request (--allowed-origins): a list of
// origins plus `self` (the origin the request itself was sent to) and `loopback`. Requests without an Origin come
// from programs (curl, bots, Node clients), not from pages a user happened to open, and are not this module's concern.
import type { IncomingMessage } from 'node:http';
import { isIP } from 'node:net';
import { AccessCode, type Refusal } from './refusal.ts';

/** The default list: pages served by this server, and pages on this machine. */
export const DEFAULT_ALLOWED_ORIGINS: readonly string[] = ['self', 'loopback'];

/** What the policy reads from a request. */
export interface OriginFacts {
  /** The Origin header (absent: not sent by a browser page). */
  origin: string | undefined;
  /** The Sec-Fetch-Site header browsers add (`same-origin`, `same-site`, `cross-site`, `none`). */
  fetchSite: string | undefined;
  /** The Host header: where the request was sent. */
  host: string | undefined;
  /** Whether the request came over TLS. */
  secure: boolean;
}

/** A parsed --allowed-origins list. */
export interface OriginPolicy {
  /** The list as given (for logs and error texts). */
  readonly entries: readonly string[];
  /** Whether a request carrying this Origin may proceed. */
  allows(origin: string, facts: Pick<OriginFacts, 'host' | 'secure'>): boolean;
  /** The refusal for a request from a page that is not allowed, or null (allowed, or not from a page). */
  check(facts: OriginFacts): Refusal | null;
}

/** Reads the facts the policy needs from a Node request. */
export function originFacts(req: IncomingMessage): OriginFacts {
  const header = (name: string): string | undefined => {
    const v = req.headers[name];
    return typeof v === 'string' ? v : undefined;
  };
  return { origin: header('origin'), fetchSite: header('sec-fetch-site'), host: header('host'), secure: (req.socket as { encrypted?: boolean }).encrypted === true };
}

/** `scheme://host[:port]` in the form browsers send (lower case, default port left out), or null when not an origin. */
export function normalizeOrigin(text: string): string | null {
  let url: URL;
  try {
    url = new URL(text);
  } catch {
    return null;
  }
  if (url.protocol !== 'http:' && url.protocol !== 'https:') return null;
  if (url.username !== '' || url.password !== '' || url.search !== '' || url.hash !== '' || (url.pathname !== '/' && url.pathname !== '')) return null;
  return url.origin;
}

function isLoopbackHost(hostname: string): boolean {
  if (hostname === 'localhost' || hostname.endsWith('.localhost')) return true;
  if (hostname === '[::1]') return true;
  return isIP(hostname) === 4 && hostname.startsWith('127.');
}

function isIpLiteral(hostname: string): boolean {
  return isIP(hostname.startsWith('[') ? hostname.slice(1, -1) : hostname) !== 0;
}

/**
 * `self`: the page was served from the very address the request went to (Origin host:port = Host header), and that
 * address cannot have been re-pointed at this server by someone else's DNS: an IP literal, or a TLS connection (a
 * rebound name would fail the certificate check). A plain-HTTP name is never `self`: list it explicitly.
 */
function isSelf(origin: URL, facts: Pick<OriginFacts, 'host' | 'secure'>): boolean {
  if (facts.host === undefined || facts.host === '') return false;
  let target: URL;
  try {
    target = new URL(`${origin.protocol}//${facts.host}`);
  } catch {
    return false;
  }
  if (target.host !== origin.host || target.pathname !== '/') return false;
  return facts.secure || isIpLiteral(origin.hostname);
}

/** Parses an --allowed-origins value (comma-separated, or a list); throws an Error naming a bad entry. */
export function parseAllowedOrigins(spec: string | readonly string[] | undefined): OriginPolicy {
  const raw = spec === undefined ? DEFAULT_ALLOWED_ORIGINS : typeof spec === 'string' ? spec.split(',') : spec;
  const entries = raw.map((e) => e.trim()).filter((e) => e !== '');
  if (entries.length === 0) throw new Error('--allowed-origins must name at least one entry (an origin, self, loopback or *)');
  let any = false;
  let self = false;
  let loopback = false;
  const exact = new Set<string>();
  for (const e of entries) {
    if (e === '*') any = true;
    else if (e === 'self') self = true;
    else if (e === 'loopback') loopback = true;
    else {
      const o = normalizeOrigin(e);
      if (o === null) throw new Error(`--allowed-origins: "${e}" is not an origin (http[s]://host[:port], no path), self, loopback or *`);
      exact.add(o);
    }
  }
  const allows = (origin: string, facts: Pick<OriginFacts, 'host' | 'secure'>): boolean => {
    if (any) return true;
    if (exact.size > 0 && exact.has(origin)) return true;
    if (!self && !loopback) return false;
    let url: URL;
    try {
      url = new URL(origin);
    } catch {
      return false; // "null" (sandboxed frames, file: pages) and garbage
    }
    if (url.origin !== origin) return false; // not in the form browsers send
    if (loopback && isLoopbackHost(url.hostname)) return true;
    return self && isSelf(url, facts);
  };
  const shownList = entries.join(',');
  return {
    entries,
    allows,
    check(facts) {
      if (facts.origin === undefined) {
        // No Origin: a program, or (old browsers) a same-origin request. A browser that marks the request cross-site
        // but sends no Origin to check is refused.
        if (facts.fetchSite === 'cross-site' || facts.fetchSite === 'same-site') {
          return { status: 403, code: AccessCode.CrossSiteRequest, message: `a ${facts.fetchSite} browser request without an Origin header is refused` };
        }
        return null;
      }
      if (allows(facts.origin, facts)) return null;
      const shown = facts.origin.length > 100 ? `${facts.origin.slice(0, 100)}…` : facts.origin;
      return {
        status: 403,
        code: AccessCode.OriginNotAllowed,
        message: `origin ${JSON.stringify(shown)} is not allowed (allowed: ${shownList}); start the server with --allowed-origins to add it`,
      };
    },
  };
}
