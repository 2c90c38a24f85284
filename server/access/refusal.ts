// The one shape an access refusal takes (HTTP status, stable code, sentence, extra headers) and how it is written:
// as a JSON answer `{error: code, message}` to an HTTP request, or as a raw HTTP answer to a refused WebSocket upgrade.
import type { ServerResponse } from 'node:http';
import type { Duplex } from 'node:stream';

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

const STATUS_TEXT: Readonly<Record<Refusal['status'], string>> = { 401: 'Unauthorized', 403: 'Forbidden' };

function body(r: Refusal): string {
  return JSON.stringify({ error: r.code, message: r.message });
}

/** Answers an HTTP request with the refusal. */
export function sendRefusal(res: ServerResponse, r: Refusal): void {
  const text = body(r);
  res.writeHead(r.status, { ...r.headers, 'content-type': 'application/json; charset=utf-8', 'cache-control': 'no-store', 'content-length': Buffer.byteLength(text) });
  res.end(text);
}

/** Answers a WebSocket upgrade request with the refusal instead of switching protocols, then closes the socket. */
export function refuseUpgrade(socket: Duplex, r: Refusal): void {
  const text = body(r);
  const extra = Object.entries(r.headers ?? {}).map(([k, v]) => `${k}: ${v}\r\n`).join('');
  socket.end(
    `HTTP/1.1 ${r.status} ${STATUS_TEXT[r.status]}\r\nContent-Type: application/json; charset=utf-8\r\nContent-Length: ${Buffer.byteLength(text)}\r\n` +
      `Cache-Control: no-store\r\n${extra}Connection: close\r\n\r\n${text}`,
  );
}
