// What an access refusal is (HTTP status, stable code, sentence, extra headers) and how it is written, through the
// server's one error shape (server/http-errors.ts): to an HTTP request, or as raw HTTP to a refused WebSocket upgrade.
import type { ServerResponse } from 'node:http';
import type { Duplex } from 'node:stream';
import { rawErrorResponse, sendError } from '../http-errors.ts';

/** Codes of access refusals (the `error` field of the JSON body). */
export const AccessCode = {
  /** The request's Origin is not in --allowed-origins. */
  OriginNotAllowed: 'origin-not-allowed',
  /** A browser sent a cross-site request that carries no Origin to check. */
  CrossSiteRequest: 'cross-site-request',
  /** The route needs `Authorization: Bearer <admin token>` and the request has none. */
  AdminTokenRequired: 'admin-token-required',
  /** The request's bearer token is not the admin token. */
  AdminTokenWrong: 'admin-token-wrong',
} as const;
export type AccessCode = (typeof AccessCode)[keyof typeof AccessCode];

/** Why a request is refused. */
export interface Refusal {
  status: 401 | 403;
  code: AccessCode;
  message: string;
  /** Extra response headers (WWW-Authenticate on 401). */
  headers?: Readonly<Record<string, string>>;
}

/** Answers an HTTP request with the refusal. */
export function sendRefusal(res: ServerResponse, r: Refusal): void {
  sendError(res, r.status, r.code, r.message, r.headers);
}

/** Answers a WebSocket upgrade request with the refusal instead of switching protocols, then closes the socket. */
export function refuseUpgrade(socket: Duplex, r: Refusal): void {
  socket.end(rawErrorResponse(r.status, r.code, r.message, r.headers));
}
