// Unit tests of server/fleet/fleet-rooms.ts: how a fleet listing orders and labels rooms, and the moved answer.
import { describe, expect, it } from 'vitest';
import type { MemberRecord } from '../../../server/fleet/fleet-directory.ts';
import { fleetRooms, movedAnswer } from '../../../server/fleet/fleet-rooms.ts';
import { RoomMovedError, webSocketUrl } from '../../../server/fleet/room-moved.ts';
import type { RoomInfo } from '../../../server/room.ts';

const room = (id: string, clients = 0): RoomInfo => ({ id, scenario: 'character-course', clients, tick: 0, bodies: 1, params: {}, netMode: 'snapshot', ticksPerSecond: 60, slow: false, tickMsP99: 1, tickCpuMsP99: 1, tickGapMsMax: 17 });
const member = (id: string, url: string, rooms: RoomInfo[]): MemberRecord => ({ id, url, wsUrl: webSocketUrl(url), capacity: { rooms: 6, connections: 256 }, players: 0, rooms, startedAt: '' });

describe('fleetRooms', () => {
  it('lists this server\'s rooms first, then the others\' by server URL and id, each naming its server', () => {
    const self = { id: 'a', url: 'http://a:1/', wsUrl: 'ws://a:1/' };
    const members = [member('c', 'http://c:1/', [room('zeta'), room('alpha')]), member('b', 'http://b:1/', [room('mid')]), member('a', 'http://a:1/', [room('stale')])];
    expect(fleetRooms(self, [room('default', 2), room('mine')], members).map((r) => `${r.id}@${r.server.id}`)).toEqual(['default@a', 'mine@a', 'mid@b', 'alpha@c', 'zeta@c']);
  });

  it('leaves out other servers\' default rooms and ids listed already', () => {
    const self = { id: 'a', url: 'http://a:1/', wsUrl: 'ws://a:1/' };
    const rooms = fleetRooms(self, [room('default'), room('dup')], [member('b', 'http://b:1/', [room('default'), room('dup'), room('only-b')])]);
    expect(rooms.map((r) => `${r.id}@${r.server.id}`)).toEqual(['default@a', 'dup@a', 'only-b@b']);
  });
});

describe('movedAnswer', () => {
  it('answers 409 room-moved with the room id and both URLs of its server', () => {
    const e = movedAnswer(new RoomMovedError('arena', { id: 'b', url: 'https://b.example:8443/', wsUrl: webSocketUrl('https://b.example:8443/') }));
    expect([e.status, e.code, e.details]).toEqual([409, 'room-moved', { roomId: 'arena', url: 'https://b.example:8443/', wsUrl: 'wss://b.example:8443/' }]);
  });
});
