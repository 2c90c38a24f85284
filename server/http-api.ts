// The server's HttpApi: what the rooms and seats API, health, scenarios and metrics routes answer, over a GameServer. Refusals
// are HttpErrors with a code that says what went wrong (unknown scenario, bad parameter, room exists, …).
import type { IncomingMessage, ServerResponse } from 'node:http';
import { ErrorCode } from '../shared/protocol/opcodes.ts';
import type { ServerAccess } from './access/access-setup.ts';
import { resolveParams } from '../shared/sim/scenario.ts';
import type { FleetDirectory } from './fleet/fleet-directory.ts';
import { cachedHost, listFleetRooms, movedAnswer, playersElsewhere } from './fleet/fleet-rooms.ts';
import { RoomMovedError } from './fleet/room-moved.ts';
import type { GameServer } from './game-server.ts';
import { HttpError, HttpErrorCode } from './http-errors.ts';
import type { CreateRoomRequest, HttpApi } from './http-server.ts';
import type { Logger } from './logger.ts';
import type { ServerMetrics } from './metrics.ts';
import type { HostedRoom } from './hosted-room.ts';
import type { MonitorRoutes } from './monitor/monitor-routes.ts';
import { RoomError, type RoomInfo } from './room.ts';
import type { ScenarioSource } from './room-factory.ts';
import { DEFAULT_ROOM_ID, isRoomId } from './room-manager.ts';

/** What createHttpApi serves. */
export interface HttpApiOptions {
  game: GameServer;
  scenarios: ScenarioSource;
  metrics: ServerMetrics;
  logger: Logger;
  /** Access control: the guard every request passes first, and the seat tokens the seats route issues. */
  access: ServerAccess;
  staticFiles(req: IncomingMessage, res: ServerResponse): Promise<boolean>;
  /** The monitor's routes; absent: no /monitor. */
  monitor?: MonitorRoutes;
  /** With a fleet (`--redis`): lists every server's rooms and answers for rooms hosted elsewhere. */
  fleet?: FleetDirectory;
}

const quote = (s: string): string => JSON.stringify(s.length > 64 ? `${s.slice(0, 64)}…` : s);

/** A room the manager could not open, as an HTTP answer (unexpected failures are logged). */
function creationRefused(error: unknown, logger: Logger): HttpError {
  if (error instanceof HttpError) return error;
  if (error instanceof RoomMovedError) return movedAnswer(error);
  if (error instanceof RoomError && error.code === ErrorCode.ServerFull) return new HttpError(503, HttpErrorCode.ServerFull, error.message);
  const message = error instanceof Error ? error.message : String(error);
  logger.error({ err: error }, 'opening a room over HTTP failed');
  return new HttpError(500, HttpErrorCode.Internal, message);
}

/** The HttpApi of a running GameServer. */
export function createHttpApi(opts: HttpApiOptions): HttpApi {
  const { game, scenarios } = opts;

  // A room asked for by id that is already open: the same room when scenario, given parameters and net mode match,
  // else 409. A room this request just opened keeps the mode its cost allowed (its netModeNote says why).
  const matchExisting = (room: HostedRoom, req: CreateRoomRequest, params: Readonly<Record<string, number>>, opened = false): RoomInfo => {
    if (room.scenarioName !== req.scenario) {
      throw new HttpError(409, HttpErrorCode.RoomExists, `room ${quote(room.id)} is open with scenario ${quote(room.scenarioName)}, not ${quote(req.scenario)}`);
    }
    const info = room.info();
    if (!opened && req.netMode !== undefined && req.netMode !== 'auto' && req.netMode !== info.netMode) {
      throw new HttpError(409, HttpErrorCode.RoomExists, `room ${quote(room.id)} is open in ${info.netMode} mode, not ${req.netMode}${info.netModeNote ? ` (${info.netModeNote})` : ''}`);
    }
    for (const key of Object.keys(req.params ?? {})) {
      if (room.params[key] !== params[key]) throw new HttpError(409, HttpErrorCode.RoomExists, `room ${quote(room.id)} is open with ${key}=${room.params[key]}, not ${params[key]}`);
    }
    return info;
  };

  return {
    health: () => (opts.fleet ? { ...game.health(), fleet: opts.fleet.status() } : game.health()),
    listRooms: () => (opts.fleet ? listFleetRooms(opts.fleet, game.listRooms()) : game.listRooms()),
    listScenarios: () =>
      scenarios.names().map((n) => {
        const s = scenarios.get(n)!;
        return { name: s.name, description: s.description, params: s.params };
      }),
    async createRoom(req) {
      if (game.isClosing) throw new HttpError(503, HttpErrorCode.ShuttingDown, 'the server is shutting down');
      const def = scenarios.get(req.scenario);
      if (!def) throw new HttpError(400, HttpErrorCode.UnknownScenario, `unknown scenario ${quote(req.scenario)} (known: ${scenarios.names().join(', ')})`);
      let params: Readonly<Record<string, number>>;
      try {
        params = resolveParams(def, req.params ?? {});
      } catch (error) {
        throw new HttpError(400, HttpErrorCode.BadParam, error instanceof Error ? error.message : String(error));
      }
      if (req.roomId === undefined) {
        const room = await game.rooms.resolve({ scenario: req.scenario, params: req.params, netMode: req.netMode }).catch((e: unknown) => Promise.reject(creationRefused(e, opts.logger)));
        return { room: room.info(), created: true };
      }
      if (!isRoomId(req.roomId)) throw new HttpError(400, HttpErrorCode.BadRoomId, `room id must be 1-64 characters of A-Z a-z 0-9 _ -, got ${quote(req.roomId)}`);
      const existing = game.rooms.get(req.roomId);
      if (existing) return { room: matchExisting(existing, req, params), created: false };
      const room = await game.rooms.create(req.roomId, req.scenario, req.params ?? {}, req.netMode).catch((e: unknown) => Promise.reject(creationRefused(e, opts.logger)));
      // Another request may have been opening the same id at the same moment: it must agree too.
      return { room: matchExisting(room, req, params, true), created: true };
    },
    async deleteRoom(id) {
      if (id === DEFAULT_ROOM_ID) throw new HttpError(409, HttpErrorCode.DefaultRoom, 'the default room stays open while the server runs');
      const room = game.rooms.get(id);
      if (!room && opts.fleet && isRoomId(id)) await opts.fleet.locate(id).catch((e: unknown) => Promise.reject(e instanceof RoomMovedError ? movedAnswer(e) : e));
      if (!room) throw new HttpError(404, HttpErrorCode.RoomNotFound, `no room ${quote(id)}`);
      const info = room.info();
      await room.close(`room ${id} was closed through the server's HTTP API`);
      opts.logger.info({ room: id, clients: info.clients }, 'room closed over HTTP');
      return info;
    },
    async roomPlayers(roomId) {
      // A page joined to a room of another fleet server through this one asks here: the host answers for it.
      const remote = !game.rooms.get(roomId) && opts.fleet && isRoomId(roomId) ? await playersElsewhere(opts.fleet, roomId) : null;
      if (remote) return remote;
      if (!game.rooms.get(roomId)) throw new HttpError(404, HttpErrorCode.RoomNotFound, `no room ${quote(roomId)} is open`);
      return game
        .sessionList()
        .filter((s) => !s.ended && s.currentRoom?.id === roomId)
        .map((s) => ({ playerId: s.player, name: s.link.name }))
        .sort((a, b) => a.playerId - b.playerId);
    },
    reserveSeat(roomId, req) {
      const elsewhere = !game.rooms.get(roomId) && opts.fleet ? cachedHost(opts.fleet, roomId) : null;
      if (elsewhere) throw movedAnswer(new RoomMovedError(roomId, elsewhere));
      if (!game.rooms.get(roomId)) throw new HttpError(404, HttpErrorCode.RoomNotFound, `no room ${quote(roomId)} is open`);
      const seat = opts.access.seats.issue(roomId, req.ttlSeconds === undefined ? undefined : req.ttlSeconds * 1000);
      return { token: seat.token, roomId: seat.roomId, seatId: seat.seatId, expiresAt: new Date(seat.expiresAtMs).toISOString() };
    },
    async moveRoom(roomId, worker) {
      const pool = game.workers;
      if (!pool) throw new HttpError(409, HttpErrorCode.CannotMove, 'rooms run on the main thread (--room-workers 0): there is no other worker to move to');
      const from = pool.workers().find((t) => t.rooms.has(roomId));
      if (!from) throw new HttpError(404, HttpErrorCode.RoomNotFound, `no room ${quote(roomId)} is open in a room worker`);
      if (worker === from.index) throw new HttpError(409, HttpErrorCode.CannotMove, `room ${quote(roomId)} already runs in worker ${worker}`);
      if (pool.isMoving) throw new HttpError(409, HttpErrorCode.CannotMove, 'another room is moving; try again shortly');
      return pool.moveRoom(roomId, { to: worker, reason: 'asked for over the HTTP API' });
    },
    metrics: () => game.renderMetrics(),
    authorize: opts.access.authorize,
    staticFiles: (req, res) => opts.staticFiles(req, res),
    monitor: opts.monitor,
  };
}
