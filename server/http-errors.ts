// The one shape of every HTTP error answer, `{error: code, message}`: the codes, an Error that carries a status and a
// code through the route handlers, and the helpers that write it — to an HTTP response, or as raw HTTP bytes to a
// socket refused before HTTP handling (a WebSocket upgrade, the listening gate). Every refusal is written here.
import type { ServerResponse } from 'node:http';

/** Machine-readable codes of HTTP error answers (the WebSocket protocol has its own, in shared/protocol). */
export const HttpErrorCode = {
  /** The request target is not a valid URL (e.g. malformed percent-encoding). */
  BadUrl: 'bad-url',
  /** The body is not JSON. */
  BadJson: 'bad-json',
  /** The body is JSON but not the object the route takes, or a field has the wrong type. */
  BadBody: 'bad-body',
  /** The body has a field the route does not know (named in the message). */
  UnknownField: 'unknown-field',
  UnknownScenario: 'unknown-scenario',
  /** A scenario parameter is unknown or out of range. */
  BadParam: 'bad-param',
  /** A room id that does not match [A-Za-z0-9_-]{1,64}. */
  BadRoomId: 'bad-room-id',
  /** A room with that id is open with another scenario or other parameters. */
  RoomExists: 'room-exists',
  RoomNotFound: 'room-not-found',
  /** The default room cannot be closed over HTTP. */
  DefaultRoom: 'default-room',
  NotFound: 'not-found',
  /** A path outside what the server serves. */
  Forbidden: 'forbidden',
  MethodNotAllowed: 'method-not-allowed',
  BodyTooLarge: 'body-too-large',
  /** The room is hosted by another server of the fleet: the answer's `url` names it. */
  RoomMoved: 'room-moved',
  /** The room cannot move to another room worker now (no workers, already there, or another room is moving). */
  CannotMove: 'cannot-move',
  /** The rooms limit is reached, or the server has no physics memory left for another room. */
  ServerFull: 'server-full',
  ShuttingDown: 'shutting-down',
  /** Too many requests from one address for now (Retry-After says when to try again). */
  RateLimited: 'rate-limited',
  Internal: 'internal',
} as const;
export type HttpErrorCode = (typeof HttpErrorCode)[keyof typeof HttpErrorCode];

/** A refusal a route handler throws; the router answers it with sendError. */
export class HttpError extends Error {
  readonly status: number;
  readonly code: HttpErrorCode;
  /** Extra response headers (Allow, Retry-After). */
  readonly headers: Readonly<Record<string, string>>;
  /** Extra fields of the answer beside error and message (a moved room's `url`). */
  readonly details: Readonly<Record<string, unknown>>;
  constructor(status: number, code: HttpErrorCode, message: string, headers: Record<string, string> = {}, details: Record<string, unknown> = {}) {
    super(message);
    this.name = 'HttpError';
    this.status = status;
    this.code = code;
    this.headers = headers;
    this.details = details;
  }
}

/** Writes a JSON answer (never cached). */
export function sendJson(res: ServerResponse, status: number, value: unknown, headers: Readonly<Record<string, string>> = {}): void {
  const body = JSON.stringify(value);
  res.writeHead(status, { ...headers, 'content-type': 'application/json; charset=utf-8', 'cache-control': 'no-store', 'content-length': Buffer.byteLength(body) });
  res.end(body);
}

/** Writes the error answer `{error: code, message, ...details}` (codes: HttpErrorCode, or access control's AccessCode). */
export function sendError(res: ServerResponse, status: number, code: string, message: string, headers: Readonly<Record<string, string>> = {}, details: Readonly<Record<string, unknown>> = {}): void {
  sendJson(res, status, { ...details, error: code, message }, headers);
}

const STATUS_TEXT: Readonly<Record<number, string>> = { 401: 'Unauthorized', 403: 'Forbidden', 429: 'Too Many Requests', 503: 'Service Unavailable' };

/** The error answer `{error: code, message}` as a whole HTTP/1.1 response that closes the connection. */
export function rawErrorResponse(status: number, code: string, message: string, headers: Readonly<Record<string, string>> = {}): string {
  const body = JSON.stringify({ error: code, message });
  const extra = Object.entries(headers)
    .map(([k, v]) => `${k}: ${v}\r\n`)
    .join('');
  return (
    `HTTP/1.1 ${status} ${STATUS_TEXT[status] ?? 'Error'}\r\nContent-Type: application/json; charset=utf-8\r\nContent-Length: ${Buffer.byteLength(body)}\r\n` +
    `Cache-Control: no-store\r\n${extra}Connection: close\r\n\r\n${body}`
  );
}
