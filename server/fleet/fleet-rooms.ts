// What the HTTP API says about the fleet: the rooms of every member (each naming the server that hosts it), and the
// JSON answer for a room hosted elsewhere. Reads are bounded: a slow directory answers from the last read instead.
import { HttpError, HttpErrorCode } from '../http-errors.ts';
import type { RoomInfo } from '../room.ts';
import { DEFAULT_ROOM_ID } from '../room-manager.ts';
import type { FleetDirectory, MemberRecord } from './fleet-directory.ts';
import { RoomMovedError, type MemberAddress } from './room-moved.ts';

/** A room in a fleet listing: where it runs. */
export interface FleetRoomInfo extends RoomInfo {
  server: { id: string; url: string };
}

/** How long a listing waits for the directory before it answers from the last read. */
export const LIST_WAIT_MS = 300;

/**
 * The fleet's rooms: this process's own first (live numbers), then other members' as they last published, by server
 * URL and id. Other members' default rooms are left out: `default` always means the default room of the server asked.
 */
export function fleetRooms(self: MemberAddress, local: readonly RoomInfo[], members: readonly MemberRecord[]): FleetRoomInfo[] {
  const out: FleetRoomInfo[] = local.map((r) => ({ ...r, server: { id: self.id, url: self.url } }));
  const seen = new Set(local.map((r) => r.id));
  const others = members.filter((m) => m.id !== self.id).sort((a, b) => (a.url < b.url ? -1 : a.url > b.url ? 1 : 0));
  for (const m of others) {
    const rooms = [...m.rooms].sort((a, b) => (a.id < b.id ? -1 : a.id > b.id ? 1 : 0));
    for (const r of rooms) {
      if (r.id === DEFAULT_ROOM_ID || seen.has(r.id)) continue;
      seen.add(r.id);
      out.push({ ...r, server: { id: m.id, url: m.url } });
    }
  }
  return out;
}

/** The fleet's rooms, read now when the directory answers within LIST_WAIT_MS, else from its last read. */
export async function listFleetRooms(directory: FleetDirectory, local: readonly RoomInfo[]): Promise<FleetRoomInfo[]> {
  let timer: NodeJS.Timeout | undefined;
  const late = new Promise<null>((resolve) => (timer = setTimeout(() => resolve(null), LIST_WAIT_MS)));
  const members = await Promise.race([directory.members().catch(() => null), late]);
  clearTimeout(timer);
  return fleetRooms(directory, local, members ?? directory.cachedMembers());
}

/** The member that hosts `roomId` according to the last read of the directory, or null. */
export function cachedHost(directory: FleetDirectory, roomId: string): MemberAddress | null {
  if (roomId === DEFAULT_ROOM_ID) return null;
  for (const m of directory.cachedMembers()) {
    if (m.id !== directory.id && m.rooms.some((r) => r.id === roomId)) return { id: m.id, url: m.url, wsUrl: m.wsUrl };
  }
  return null;
}

/** How long asking another member for a room's players may take. */
const PLAYERS_WAIT_MS = 1000;

/**
 * The players of a room another member hosts, asked of that member (GET /api/rooms/ID/players there), or null when no
 * other member hosts it or it does not answer in time.
 */
export async function playersElsewhere(directory: FleetDirectory, roomId: string): Promise<Array<{ playerId: number; name: string }> | null> {
  let host: MemberAddress;
  try {
    await directory.locate(roomId);
    return null;
  } catch (error) {
    if (!(error instanceof RoomMovedError)) return null;
    host = error.host;
  }
  try {
    const res = await fetch(new URL(`api/rooms/${encodeURIComponent(roomId)}/players`, host.url), { headers: { accept: 'application/json' }, signal: AbortSignal.timeout(PLAYERS_WAIT_MS) });
    if (!res.ok) return null;
    const body = (await res.json()) as { players?: unknown };
    if (!Array.isArray(body.players)) return null;
    return body.players
      .filter((p): p is { playerId: number; name: string } => typeof (p as { playerId?: unknown }).playerId === 'number' && typeof (p as { name?: unknown }).name === 'string')
      .map((p) => ({ playerId: p.playerId, name: p.name.slice(0, 64) }));
  } catch {
    return null;
  }
}

/** The HTTP answer for a room hosted by another member: 409 `room-moved` with its URLs. */
export function movedAnswer(error: RoomMovedError): HttpError {
  return new HttpError(409, HttpErrorCode.RoomMoved, error.message, {}, { roomId: error.roomId, url: error.host.url, wsUrl: error.host.wsUrl });
}
