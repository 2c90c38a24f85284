// Access rules of the HTTP routes: every mutating request (anything but GET/HEAD/OPTIONS) must come from an allowed
// origin; mutating /api/ routes, /metrics and everything under /monitor/ need the admin token when one is set. Other
// reads stay open (lobby pages).
import type { IncomingMessage } from 'node:http';
import type { AdminAuth } from './admin-auth.ts';
import { originFacts, type OriginPolicy } from './origin-policy.ts';
import type { Refusal } from './refusal.ts';

const SAFE_METHODS: ReadonlySet<string> = new Set(['GET', 'HEAD', 'OPTIONS']);

/** What the guard enforces. */
export interface HttpGuardOptions {
  origins: OriginPolicy;
  /** Null: no admin token set (operator routes are open to allowed origins and to programs). */
  admin: AdminAuth | null;
  /** Called with the code of every refusal (metrics). */
  onRefused?(refusal: Refusal): void;
}

/** Whether a route is an operator route (needs the admin token when one is set). */
export function isAdminRoute(method: string, path: string): boolean {
  if (path === '/metrics') return true;
  // The monitor's data and actions; its page (/monitor) holds no data and asks for the token itself.
  if (path.startsWith('/monitor/')) return true;
  return !SAFE_METHODS.has(method) && (path === '/api' || path.startsWith('/api/'));
}

/** The guard: the refusal for a request, or null to let it through to its route. */
export function createHttpGuard(opts: HttpGuardOptions): (req: IncomingMessage, method: string, path: string) => Refusal | null {
  return (req, method, path) => {
    let refusal: Refusal | null = null;
    if (!SAFE_METHODS.has(method)) refusal = opts.origins.check(originFacts(req));
    if (refusal === null && opts.admin !== null && isAdminRoute(method, path)) refusal = opts.admin.check(req.headers.authorization);
    if (refusal !== null) opts.onRefused?.(refusal);
    return refusal;
  };
}
