// The HTTP half of the server's single port: /healthz, /metrics, the rooms and seats API and the static client files.
// Routing and request parsing only; what the answers contain (and who may ask) comes from the HttpApi passed in.
import { createServer, type IncomingMessage, type Server, type ServerResponse } from 'node:http';
import { ErrorCode } from '../shared/protocol/opcodes.ts';
import { sendRefusal, type Refusal } from './access/refusal.ts';
import { parseSeatRequest, type SeatAnswer, type SeatRequest } from './access/seat-request.ts';
import type { RoomInfo } from './room.ts';

/** What the HTTP routes read and do. */
export interface HttpApi {
  /** GET /healthz body; `ok: false` answers 503. */
  health(): { ok: boolean } & Record<string, unknown>;
  /** GET /api/rooms. */
  listRooms(): RoomInfo[];
  /** GET /api/scenarios. */
  listScenarios(): unknown[];
  /** POST /api/rooms {scenario, params?, roomId?}: creates (or returns) a room. Throws an Error with `code` on refusal. */
  createRoom(req: { scenario: string; params?: Record<string, number>; roomId?: string }): Promise<RoomInfo>;
  /** POST /api/rooms/ID/seats {ttlSeconds?}: a seat token for that room. Throws an Error with `code` on refusal. */
  reserveSeat(roomId: string, req: SeatRequest): SeatAnswer;
  /** GET /metrics. */
  metrics(): Promise<{ body: string; contentType: string }>;
  /** Access rules, checked before any route: a refusal is the whole answer. */
  authorize?(req: IncomingMessage, method: string, path: string): Refusal | null;
  /** Anything else: static files; resolves true when it answered. */
  staticFiles(req: IncomingMessage, res: ServerResponse): Promise<boolean>;
}

const MAX_BODY_BYTES = 4096;

function sendJson(res: ServerResponse, status: number, value: unknown): void {
  const body = JSON.stringify(value);
  res.writeHead(status, { 'content-type': 'application/json; charset=utf-8', 'cache-control': 'no-store', 'content-length': Buffer.byteLength(body) });
  res.end(body);
}

function readBody(req: IncomingMessage): Promise<string> {
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
        reject(Object.assign(new Error(`request body over ${MAX_BODY_BYTES} bytes`), { status: 413 }));
        return;
      }
      chunks.push(c);
    });
    req.on('end', () => resolve(Buffer.concat(chunks).toString('utf8')));
    req.on('error', reject);
  });
}

function parseCreateRoom(text: string): { scenario: string; params?: Record<string, number>; roomId?: string } {
  let v: unknown;
  try {
    v = JSON.parse(text);
  } catch {
    throw Object.assign(new Error('body must be JSON: {"scenario": "name", "params"?: {...}, "roomId"?: "id"}'), { status: 400 });
  }
  if (v === null || typeof v !== 'object' || Array.isArray(v)) throw Object.assign(new Error('body must be a JSON object'), { status: 400 });
  const o = v as Record<string, unknown>;
  if (typeof o.scenario !== 'string' || o.scenario.length === 0 || o.scenario.length > 64) throw Object.assign(new Error('"scenario" must be a scenario name'), { status: 400 });
  const out: { scenario: string; params?: Record<string, number>; roomId?: string } = { scenario: o.scenario };
  if (o.roomId !== undefined) {
    if (typeof o.roomId !== 'string') throw Object.assign(new Error('"roomId" must be a string'), { status: 400 });
    out.roomId = o.roomId;
  }
  if (o.params !== undefined) {
    if (o.params === null || typeof o.params !== 'object' || Array.isArray(o.params)) throw Object.assign(new Error('"params" must be an object of numbers'), { status: 400 });
    const params: Record<string, number> = {};
    for (const [k, val] of Object.entries(o.params as Record<string, unknown>)) {
      if (typeof val !== 'number' || !Number.isFinite(val)) throw Object.assign(new Error(`param "${k}" must be a finite number`), { status: 400 });
      params[k] = val;
    }
    out.params = params;
  }
  return out;
}

const ERROR_STATUS: Readonly<Record<string, number>> = {
  [ErrorCode.BadMessage]: 400,
  [ErrorCode.RoomNotFound]: 404,
  [ErrorCode.RoomFull]: 409,
  [ErrorCode.ServerFull]: 503,
  [ErrorCode.Internal]: 500,
};

async function route(api: HttpApi, req: IncomingMessage, res: ServerResponse): Promise<void> {
  const url = new URL(req.url ?? '/', 'http://localhost');
  const path = url.pathname;
  const method = req.method ?? 'GET';
  const refusal = api.authorize?.(req, method, path) ?? null;
  if (refusal !== null) {
    sendRefusal(res, refusal);
    return;
  }
  if (path === '/healthz' && (method === 'GET' || method === 'HEAD')) {
    const h = api.health();
    sendJson(res, h.ok ? 200 : 503, h);
    return;
  }
  if (path === '/metrics' && method === 'GET') {
    const { body, contentType } = await api.metrics();
    res.writeHead(200, { 'content-type': contentType, 'cache-control': 'no-store' });
    res.end(body);
    return;
  }
  if (path === '/api/scenarios' && method === 'GET') {
    sendJson(res, 200, { scenarios: api.listScenarios() });
    return;
  }
  if (path === '/api/rooms' && method === 'GET') {
    sendJson(res, 200, { rooms: api.listRooms() });
    return;
  }
  if (path === '/api/rooms' && method === 'POST') {
    try {
      const room = await api.createRoom(parseCreateRoom(await readBody(req)));
      sendJson(res, 201, { room });
    } catch (error) {
      const e = error as Error & { status?: number; code?: string };
      const status = e.status ?? (e.code !== undefined ? (ERROR_STATUS[e.code] ?? 500) : 500);
      sendJson(res, status, { error: e.message, code: e.code ?? 'bad-request' });
    }
    return;
  }
  const seatMatch = /^\/api\/rooms\/([^/]+)\/seats$/.exec(path);
  if (seatMatch && method === 'POST') {
    try {
      const seat = api.reserveSeat(decodeURIComponent(seatMatch[1]), parseSeatRequest(await readBody(req)));
      sendJson(res, 201, { seat });
    } catch (error) {
      if (error instanceof URIError) {
        sendJson(res, 400, { error: 'bad-request', message: 'the room id in the path is not valid percent-encoding' });
        return;
      }
      const e = error as Error & { status?: number; code?: string };
      const status = e.status ?? (e.code !== undefined ? (ERROR_STATUS[e.code] ?? 500) : 500);
      sendJson(res, status, { error: e.code ?? (status === 413 ? 'body-too-large' : 'bad-request'), message: e.message });
    }
    return;
  }
  const roomMatch = /^\/api\/rooms\/([^/]+)$/.exec(path);
  if (roomMatch && method === 'GET') {
    const room = api.listRooms().find((r) => r.id === decodeURIComponent(roomMatch[1]));
    if (room) sendJson(res, 200, { room });
    else sendJson(res, 404, { error: `no room "${decodeURIComponent(roomMatch[1])}"`, code: 'room-not-found' });
    return;
  }
  if (path.startsWith('/api/') || path === '/healthz' || path === '/metrics') {
    sendJson(res, 405, { error: `${method} ${path} is not supported`, code: 'method-not-allowed' });
    return;
  }
  if (await api.staticFiles(req, res)) return;
  res.writeHead(405, { 'content-type': 'text/plain; charset=utf-8', allow: 'GET, HEAD' }).end(`${method} not allowed\n`);
}

/** An HTTP server answering the routes above; never throws out of a request (failures answer 500). */
export function createHttpServer(api: HttpApi, onError?: (error: unknown) => void): Server {
  return createServer((req, res) => {
    route(api, req, res).catch((error: unknown) => {
      onError?.(error);
      if (!res.headersSent) sendJson(res, 500, { error: 'internal error', code: 'internal' });
      else res.destroy();
    });
  });
}
