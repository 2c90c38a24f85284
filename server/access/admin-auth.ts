// The admin token (--admin-token or TAOS_ADMIN_TOKEN): when set, operator routes need `Authorization: Bearer <token>`.
// The comparison is constant-time (digests of both sides), and the token itself is never logged or echoed.
import { createHash, timingSafeEqual } from 'node:crypto';
import { AccessCode, type Refusal } from './refusal.ts';

/** Shortest admin token accepted (e.g. `openssl rand -hex 32` gives 64 characters). */
export const MIN_ADMIN_TOKEN_LENGTH = 16;
/** Environment variable the serve command reads the admin token from (keeps it out of `ps` output). */
export const ADMIN_TOKEN_ENV = 'TAOS_ADMIN_TOKEN';

const TOKEN_CHARS = /^[\x21-\x7e]+$/;
const CHALLENGE = 'Bearer realm="taos-physics"';

function digest(text: string): Buffer {
  return createHash('sha256').update(text, 'utf8').digest();
}

/** Throws a clear Error when `token` is too short or has characters an HTTP header cannot carry. */
export function checkAdminTokenText(token: string, label = '--admin-token'): void {
  if (token.length < MIN_ADMIN_TOKEN_LENGTH) throw new Error(`${label} must be at least ${MIN_ADMIN_TOKEN_LENGTH} characters (e.g. the output of \`openssl rand -hex 32\`)`);
  if (!TOKEN_CHARS.test(token)) throw new Error(`${label} must be printable ASCII without spaces`);
}

/** Checks bearer tokens against one admin token. */
export class AdminAuth {
  private readonly expected: Buffer;

  /** Throws (see checkAdminTokenText) for an unusable token. */
  constructor(token: string) {
    checkAdminTokenText(token);
    this.expected = digest(token);
  }

  /** The refusal for an Authorization header that does not carry the admin token, or null when it does. */
  check(authorization: string | undefined): Refusal | null {
    const m = authorization === undefined ? null : /^Bearer +(\S+) *$/i.exec(authorization);
    if (m === null) {
      return {
        status: 401,
        code: AccessCode.AdminTokenRequired,
        message: 'this route needs the admin token: send "Authorization: Bearer <token>"',
        headers: { 'WWW-Authenticate': CHALLENGE },
      };
    }
    // Digests have one length, so the comparison takes the same time whatever was sent.
    if (!timingSafeEqual(digest(m[1]), this.expected)) {
      return { status: 403, code: AccessCode.AdminTokenWrong, message: 'the bearer token is not the admin token' };
    }
    return null;
  }
}
