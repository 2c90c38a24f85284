// The HTTP half of the server's single port: /healthz, /metrics, the rooms and seats API, the monitor and the static
// client files.
// Routing and request parsing only; what the answers contain (and who may ask) comes from the HttpApi passed in.
// Every refusal is answered as `{error: code, message}` (server/http-errors.ts, server/access/refusal.ts).
import { createServer, type IncomingMessage, type RequestListener, type Server, type ServerResponse } from 'node:http';
import { createServer as createHttpsServer, type Server as HttpsServer } from 'node:https';
import { ErrorCode } from '../shared/protocol/opcodes.ts';
import { sendRefusal, type Refusal } from './access/refusal.ts';
import { parseSeatRequest, type SeatAnswer, type SeatRequest } from './access/seat-request.ts';
import { HttpError, HttpErrorCode, sendError, sendJson } from './http-errors.ts';
import type { MonitorRoutes } from './monitor/monitor-routes.ts';
import { isNetModeRequest, type NetModeRequest } from './net-mode-policy.ts';
import { RoomError, type RoomInfo } from './room.ts';
import type { RoomMoveSummary } from './workers/remote-room.ts';

/** What POST /api/rooms asks for. */
export interface CreateRoomRequest {
  scenario: string;
  params?: Record<string, number>;
  roomId?: string;
  /** 'snapshot', 'predict' or 'auto' (default: the server's --net-mode). */
  netMode?: NetModeRequest;
}

/** What the HTTP routes read and do. Methods refuse by throwing an HttpError (or a RoomError, mapped by its code). */
export interface HttpApi {
  /** GET /healthz body; `ok: false` answers 503. */
  health(): { ok: boolean } & Record<string, unknown>;
  /** GET /api/rooms (with a fleet: every server's rooms, each naming its server). */
  listRooms(): RoomInfo[] | Promise<RoomInfo[]>;
  /** GET /api/scenarios. */
  listScenarios(): unknown[];
  /** POST /api/rooms: opens a room, or returns the open room with that id when it matches (`created: false`). */
  createRoom(req: CreateRoomRequest): Promise<{ room: RoomInfo; created: boolean }>;
  /** DELETE /api/rooms/:id: closes the room (its players get a bye saying so); resolves with its last summary. */
  deleteRoom(id: string): Promise<RoomInfo>;
  /** GET /api/rooms/ID/players: the connected players' ids and display names (what the room's feed shows anyway). */
  roomPlayers?(roomId: string): Array<{ playerId: number; name: string }> | Promise<Array<{ playerId: number; name: string }>>;
  /** POST /api/rooms/ID/seats {ttlSeconds?}: a seat token for that room (an HttpError or RoomError on refusal). */
  reserveSeat(roomId: string, req: SeatRequest): SeatAnswer;
  /** POST /api/rooms/ID/move {worker?}: moves the room to another room worker (absent: no room workers). */
  moveRoom?(roomId: string, worker: number | undefined): Promise<RoomMoveSummary>;
  /** GET /metrics. */
  metrics(): Promise<{ body: string; contentType: string }>;
  /** GET /monitor and its data and actions (server/monitor/monitor-routes.ts); absent: no monitor. */
  monitor?: MonitorRoutes;
  /** Access rules, checked before any route: a refusal is the whole answer. */
  authorize?(req: IncomingMessage, method: string, path: string): Refusal | null;
  /** Anything else: static files; resolves true when it answered. */
  staticFiles(req: IncomingMessage, res: ServerResponse): Promise<boolean>;
}

/** Largest request body (POST /api/rooms) in bytes. */
export const MAX_BODY_BYTES = 4096;

function readBody(req: IncomingMessage): Promise<string> {
  const tooLarge = (): HttpError => new HttpError(413, HttpErrorCode.BodyTooLarge, `request body over ${MAX_BODY_BYTES} bytes`);
  const declared = Number(req.headers['content-length']);
  if (Number.isFinite(declared) && declared > MAX_BODY_BYTES) {
    req.resume(); // drain without keeping it, so the answer can be read
    return Promise.reject(tooLarge());
  }
  return new Promise((resolve, reject) => {
    const chunks: Buffer[] = [];
    let size = 0;
    let refused = false;
    req.on('data', (c: Buffer) => {
      if (refused) return; // drain the rest without keeping it, so the 413 answer can be read
      size += c.length;
      if (size > MAX_BODY_BYTES) {
        refused = true;
        chunks.length = 0;
        reject(tooLarge());
        return;
      }
      chunks.push(c);
    });
    req.on('end', () => resolve(Buffer.concat(chunks).toString('utf8')));
    req.on('error', reject);
  });
}

const CREATE_FIELDS = ['scenario', 'params', 'roomId', 'netMode'] as const;
const CREATE_SHAPE = '{"scenario": "name", "params"?: {"key": number}, "roomId"?: "id", "netMode"?: "snapshot" | "predict" | "auto"}';

/** Parses and type-checks a POST /api/rooms body; names the first unknown or mistyped field. */
export function parseCreateRoom(text: string): CreateRoomRequest {
  let v: unknown;
  try {
    v = JSON.parse(text);
  } catch {
    throw new HttpError(400, HttpErrorCode.BadJson, `the body must be JSON: ${CREATE_SHAPE}`);
  }
  if (v === null || typeof v !== 'object' || Array.isArray(v)) throw new HttpError(400, HttpErrorCode.BadBody, `the body must be a JSON object: ${CREATE_SHAPE}`);
  const o = v as Record<string, unknown>;
  const unknown = Object.keys(o).filter((k) => !(CREATE_FIELDS as readonly string[]).includes(k));
  if (unknown.length > 0) {
    const names = unknown.slice(0, 5).map((k) => JSON.stringify(k.slice(0, 64))).join(', ');
    throw new HttpError(400, HttpErrorCode.UnknownField, `unknown field${unknown.length > 1 ? 's' : ''} ${names}: POST /api/rooms takes ${CREATE_FIELDS.join(', ')}`);
  }
  if (typeof o.scenario !== 'string' || o.scenario.length === 0 || o.scenario.length > 64) throw new HttpError(400, HttpErrorCode.BadBody, '"scenario" must be a scenario name (1-64 characters)');
  const out: CreateRoomRequest = { scenario: o.scenario };
  if (o.roomId !== undefined) {
    if (typeof o.roomId !== 'string') throw new HttpError(400, HttpErrorCode.BadBody, '"roomId" must be a string');
    out.roomId = o.roomId;
  }
  if (o.netMode !== undefined) {
    if (!isNetModeRequest(o.netMode)) throw new HttpError(400, HttpErrorCode.BadBody, '"netMode" must be "snapshot", "predict" or "auto"');
    out.netMode = o.netMode;
  }
  if (o.params !== undefined) {
    if (o.params === null || typeof o.params !== 'object' || Array.isArray(o.params)) throw new HttpError(400, HttpErrorCode.BadBody, '"params" must be an object of numbers');
    const params: Record<string, number> = {};
    for (const [k, val] of Object.entries(o.params as Record<string, unknown>)) {
      if (typeof val !== 'number' || !Number.isFinite(val)) throw new HttpError(400, HttpErrorCode.BadParam, `parameter ${JSON.stringify(k.slice(0, 64))} must be a finite number`);
      params[k] = val;
    }
    out.params = params;
  }
  return out;
}

/** HTTP answers for refusals the room manager words in protocol codes. */
const ROOM_ERROR_HTTP: Readonly<Record<string, readonly [number, HttpErrorCode]>> = {
  [ErrorCode.RoomNotFound]: [404, HttpErrorCode.RoomNotFound],
  [ErrorCode.ServerFull]: [503, HttpErrorCode.ServerFull],
};

/** The HttpError an exception out of a route answers as, or null for an unexpected failure (a 500). */
function asHttpError(error: unknown): HttpError | null {
  if (error instanceof HttpError) return error;
  if (error instanceof RoomError) {
    const mapped = ROOM_ERROR_HTTP[error.code];
    return mapped ? new HttpError(mapped[0], mapped[1], error.message) : null;
  }
  return null;
}

/** The body of POST /api/rooms/ID/move: empty, or {worker?: index}. */
function parseMoveRequest(body: string): number | undefined {
  let value: unknown;
  try {
    value = body.trim() === '' ? {} : JSON.parse(body);
  } catch {
    throw new HttpError(400, HttpErrorCode.BadJson, 'the body is not JSON');
  }
  if (typeof value !== 'object' || value === null || Array.isArray(value)) throw new HttpError(400, HttpErrorCode.BadBody, 'the body must be an object: {worker?}');
  for (const key of Object.keys(value)) if (key !== 'worker') throw new HttpError(400, HttpErrorCode.UnknownField, `unknown field ${JSON.stringify(key.slice(0, 64))} (known: worker)`);
  const worker = (value as { worker?: unknown }).worker;
  if (worker !== undefined && !(Number.isInteger(worker) && (worker as number) >= 0)) throw new HttpError(400, HttpErrorCode.BadBody, 'worker must be a room worker index (a whole number ≥ 0)');
  return worker as number | undefined;
}

function notAllowed(method: string, path: string, allow: string): HttpError {
  return new HttpError(405, HttpErrorCode.MethodNotAllowed, `${method} ${path} is not supported (allowed: ${allow})`, { allow });
}

function decodeSegment(segment: string): string {
  try {
    return decodeURIComponent(segment);
  } catch {
    throw new HttpError(400, HttpErrorCode.BadUrl, `malformed percent-encoding in ${JSON.stringify(segment.slice(0, 80))}`);
  }
}

async function route(api: HttpApi, req: IncomingMessage, res: ServerResponse): Promise<void> {
  let url: URL;
  try {
    url = new URL(req.url ?? '/', 'http://localhost');
  } catch {
    throw new HttpError(400, HttpErrorCode.BadUrl, 'the request target is not a valid URL');
  }
  const path = url.pathname;
  const method = req.method ?? 'GET';
  const refusal = api.authorize?.(req, method, path) ?? null;
  if (refusal !== null) {
    sendRefusal(res, refusal);
    return;
  }
  const isGet = method === 'GET' || method === 'HEAD';
  if (path === '/healthz') {
    if (!isGet) throw notAllowed(method, path, 'GET, HEAD');
    const h = api.health();
    sendJson(res, h.ok ? 200 : 503, h);
    return;
  }
  if (path === '/metrics') {
    if (method !== 'GET') throw notAllowed(method, path, 'GET');
    const { body, contentType } = await api.metrics();
    res.writeHead(200, { 'content-type': contentType, 'cache-control': 'no-store' });
    res.end(body);
    return;
  }
  if (path === '/api/scenarios') {
    if (!isGet) throw notAllowed(method, path, 'GET, HEAD');
    sendJson(res, 200, { scenarios: api.listScenarios() });
    return;
  }
  if (path === '/api/rooms') {
    if (isGet) sendJson(res, 200, { rooms: await api.listRooms() });
    else if (method === 'POST') {
      const { room, created } = await api.createRoom(parseCreateRoom(await readBody(req)));
      sendJson(res, created ? 201 : 200, { room });
    } else throw notAllowed(method, path, 'GET, HEAD, POST');
    return;
  }
  const seatMatch = /^\/api\/rooms\/([^/]+)\/seats$/.exec(path);
  if (seatMatch) {
    if (method !== 'POST') throw notAllowed(method, path, 'POST');
    const id = decodeSegment(seatMatch[1]);
    let request: SeatRequest;
    try {
      request = parseSeatRequest(await readBody(req));
    } catch (error) {
      if (error instanceof HttpError) throw error;
      throw new HttpError(400, HttpErrorCode.BadBody, error instanceof Error ? error.message : 'the body is not a seat request');
    }
    sendJson(res, 201, { seat: api.reserveSeat(id, request) });
    return;
  }
  const moveMatch = api.moveRoom ? /^\/api\/rooms\/([^/]+)\/move$/.exec(path) : null;
  if (moveMatch && api.moveRoom) {
    if (method !== 'POST') throw notAllowed(method, path, 'POST');
    sendJson(res, 200, { move: await api.moveRoom(decodeSegment(moveMatch[1]), parseMoveRequest(await readBody(req))) });
    return;
  }
  const playersMatch = api.roomPlayers ? /^\/api\/rooms\/([^/]+)\/players$/.exec(path) : null;
  if (playersMatch && api.roomPlayers) {
    if (!isGet) throw notAllowed(method, path, 'GET, HEAD');
    sendJson(res, 200, { players: await api.roomPlayers(decodeSegment(playersMatch[1])) });
    return;
  }
  const roomMatch = /^\/api\/rooms\/([^/]+)$/.exec(path);
  if (roomMatch) {
    const id = decodeSegment(roomMatch[1]);
    if (isGet) {
      const room = (await api.listRooms()).find((r) => r.id === id);
      if (!room) throw new HttpError(404, HttpErrorCode.RoomNotFound, `no room ${JSON.stringify(id.slice(0, 64))}`);
      sendJson(res, 200, { room });
    } else if (method === 'DELETE') {
      sendJson(res, 200, { room: await api.deleteRoom(id) });
    } else throw notAllowed(method, path, 'GET, HEAD, DELETE');
    return;
  }
  if (api.monitor && (path === '/monitor' || path.startsWith('/monitor/'))) {
    if (await api.monitor(req, res, method, path)) return;
    throw new HttpError(404, HttpErrorCode.NotFound, `no monitor route ${path.slice(0, 100)} (see /monitor, /monitor/state, /monitor/events)`);
  }
  if (path.startsWith('/api/')) throw new HttpError(404, HttpErrorCode.NotFound, `no API route ${path.slice(0, 100)} (see /api/rooms, /api/scenarios)`);
  if (await api.staticFiles(req, res)) return;
  throw notAllowed(method, path, 'GET, HEAD');
}

/** The request handler of the routes above; never throws (refusals answer their status, failures 500). */
export function createRequestHandler(api: HttpApi, onError?: (error: unknown) => void): RequestListener {
  return (req, res) => {
    route(api, req, res).catch((error: unknown) => {
      const refusal = asHttpError(error);
      if (refusal === null) onError?.(error);
      if (res.headersSent) {
        res.destroy();
        return;
      }
      if (refusal) sendError(res, refusal.status, refusal.code, refusal.message, refusal.headers, refusal.details);
      else sendError(res, 500, HttpErrorCode.Internal, 'internal error');
    });
  };
}

/** An HTTP server answering the routes above; HTTPS with `tls` (PEM certificate chain and key). */
export function createHttpServer(api: HttpApi, onError?: (error: unknown) => void, tls?: { cert: string | Buffer; key: string | Buffer }): Server | HttpsServer {
  const handler = createRequestHandler(api, onError);
  return tls ? createHttpsServer({ cert: tls.cert, key: tls.key }, handler) : createServer(handler);
}
