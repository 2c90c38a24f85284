// Tests for server/http-api.ts over the in-process harness: what POST and DELETE /api/rooms do to real rooms, and the
// code each refusal carries (unknown scenario, bad parameter, bad room id, room exists, default room, not found).
import { afterEach, describe, expect, it } from 'vitest';
import { createServerAccess } from '../../server/access/access-setup.ts';
import { createHttpApi } from '../../server/http-api.ts';
import { HttpError } from '../../server/http-errors.ts';
import type { HttpApi } from '../../server/http-server.ts';
import { silentLogger } from '../../server/logger.ts';
import { ByeReason } from '../../shared/protocol/index.ts';
import { scenarioList, startHarness, type Harness } from './harness.ts';
import { emptyScenario, stripScenario } from './test-scenarios.ts';

let h: Harness | null = null;
afterEach(async () => {
  await h?.close();
  h = null;
});

async function start(maxRooms?: number): Promise<HttpApi> {
  h = await startHarness({ scenarios: [stripScenario, emptyScenario], maxRooms });
  return createHttpApi({ game: h.server, scenarios: scenarioList([stripScenario, emptyScenario]), metrics: h.server.metrics, logger: silentLogger(), access: createServerAccess({}, h.server.metrics, silentLogger()), staticFiles: async () => false });
}

/** The HttpError `p` rejects with, as {status, code, message}. */
async function refusal(p: Promise<unknown>): Promise<{ status: number; code: string; message: string }> {
  const e = await p.then(
    () => null,
    (error: unknown) => error,
  );
  if (!(e instanceof HttpError)) throw new Error(`expected an HttpError, got ${String(e)}`);
  return { status: e.status, code: e.code, message: e.message };
}

describe('http-api', () => {
  it('opens a room under an id, returns the same room for the same request, and refuses another scenario with 409', async () => {
    const api = await start();
    const first = await api.createRoom({ scenario: 'test-strip', roomId: 'arena', params: { boxes: 2 } });
    expect(first).toMatchObject({ created: true, room: { id: 'arena', scenario: 'test-strip', params: { boxes: 2 } } });
    expect(await api.createRoom({ scenario: 'test-strip', roomId: 'arena', params: { boxes: 2 } })).toMatchObject({ created: false, room: { id: 'arena' } });
    expect(await refusal(api.createRoom({ scenario: 'test-empty', roomId: 'arena' }))).toEqual({
      status: 409,
      code: 'room-exists',
      message: 'room "arena" is open with scenario "test-strip", not "test-empty"',
    });
    expect(await refusal(api.createRoom({ scenario: 'test-strip', roomId: 'arena', params: { boxes: 3 } }))).toEqual({
      status: 409,
      code: 'room-exists',
      message: 'room "arena" is open with boxes=2, not 3',
    });
  });

  it('names an unknown scenario, a bad parameter and a malformed room id', async () => {
    const api = await start();
    expect(await refusal(api.createRoom({ scenario: 'nope' }))).toEqual({ status: 400, code: 'unknown-scenario', message: 'unknown scenario "nope" (known: test-strip, test-empty)' });
    expect(await refusal(api.createRoom({ scenario: 'test-strip', params: { boxes: 99 } }))).toMatchObject({ status: 400, code: 'bad-param', message: expect.stringMatching(/boxes must be in \[0, 50\], got 99/) });
    expect(await refusal(api.createRoom({ scenario: 'test-strip', params: { wheels: 1 } }))).toMatchObject({ status: 400, code: 'bad-param', message: expect.stringMatching(/unknown parameter "wheels"/) });
    expect(await refusal(api.createRoom({ scenario: 'test-strip', roomId: 'a b' }))).toMatchObject({ status: 400, code: 'bad-room-id' });
    expect(h!.server.rooms.all().map((r) => r.id)).toEqual(['default']);
  });

  it('answers the rooms limit with 503 server-full', async () => {
    const api = await start(2);
    await api.createRoom({ scenario: 'test-empty' });
    expect(await refusal(api.createRoom({ scenario: 'test-empty' }))).toMatchObject({ status: 503, code: 'server-full', message: expect.stringMatching(/limit of 2 rooms/) });
  });

  it('closes a room on DELETE and tells its players why', async () => {
    const api = await start();
    await api.createRoom({ scenario: 'test-empty', roomId: 'doomed' });
    const ann = await h!.join('ann', 'doomed');
    const info = await api.deleteRoom('doomed');
    expect(info).toMatchObject({ id: 'doomed', clients: 1 });
    expect(h!.server.rooms.get('doomed')).toBeUndefined();
    await h!.settle(() => ann.closed !== null);
    expect(ann.ofType('bye')).toEqual([{ type: 'bye', reason: ByeReason.RoomClosed, message: "room doomed was closed through the server's HTTP API" }]);
    expect(await refusal(api.deleteRoom('doomed'))).toEqual({ status: 404, code: 'room-not-found', message: 'no room "doomed"' });
    expect(await refusal(api.deleteRoom('default'))).toMatchObject({ status: 409, code: 'default-room' });
    expect(h!.server.rooms.get('default')).toBeDefined();
  });

  it('opens a room in the net mode asked for, lists it, and refuses the other mode for an open room with 409', async () => {
    const api = await start();
    const made = await api.createRoom({ scenario: 'test-strip', roomId: 'fast', netMode: 'predict' });
    expect(made).toMatchObject({ created: true, room: { id: 'fast', netMode: 'predict' } });
    expect((await api.listRooms()).find((r) => r.id === 'fast')).toMatchObject({ netMode: 'predict' });
    expect(await api.createRoom({ scenario: 'test-strip', roomId: 'fast', netMode: 'predict' })).toMatchObject({ created: false });
    expect(await refusal(api.createRoom({ scenario: 'test-strip', roomId: 'fast', netMode: 'snapshot' }))).toEqual({
      status: 409,
      code: 'room-exists',
      message: 'room "fast" is open in predict mode, not snapshot',
    });
    // No cost estimate for a test scenario: 'auto' stays on snapshots and the room list says why.
    const auto = await api.createRoom({ scenario: 'test-strip', roomId: 'plain' });
    expect(auto.room).toMatchObject({ netMode: 'snapshot', netModeNote: 'no cost estimate for scenario test-strip (its definition gives no tickCostMs): snapshot mode' });
  });
});
