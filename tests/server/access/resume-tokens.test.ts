// Tests for server/access/resume-tokens.ts through the in-process harness: a dropped link is held for the grace
// window and taken back with the welcome's resume token (same player, same character, nothing in the input record,
// the recording replays exactly); tokens are single use, expire with the window, die with a bye or a closed room.
import { mkdtempSync, readdirSync, rmSync } from 'node:fs';
import { tmpdir } from 'node:os';
import { join } from 'node:path';
import { afterAll, afterEach, describe, expect, it } from 'vitest';
import { listScenarios } from '../../../scenarios/index.ts';
import { replayLog } from '../../../cli/replay-session.ts';
import { ByeReason, ErrorCode } from '../../../shared/protocol/index.ts';
import { NEUTRAL_INPUT, type InputCommand } from '../../../shared/sim/input.ts';
import type { TickInputRecord } from '../../../shared/sim/types.ts';
import { startHarness, type Harness, type TestClient } from '../harness.ts';
import { emptyScenario, stripScenario } from '../test-scenarios.ts';

const tmp = mkdtempSync(join(tmpdir(), 'taos-resume-'));
afterAll(() => rmSync(tmp, { recursive: true, force: true }));
let h: Harness | null = null;
afterEach(async () => {
  await h?.close();
  h = null;
});

/** Sends `cmd` for the next `n` ticks, a little ahead of the server, one message per tick. */
function drive(h: Harness, c: TestClient, cmd: InputCommand, n: number): void {
  for (let i = 0; i < n; i++) {
    c.input(h.room().sim.tick + 2, [cmd]);
    h.ticks(1);
  }
}

/** Connects and sends a hello with a resume token; waits for the welcome or the close. */
async function resume(h: Harness, name: string, token: string, room: string | null = null): Promise<TestClient> {
  const c = h.connect();
  c.hello(name, room, { resumeToken: token });
  await h.settle(() => c.welcome !== null || c.closed !== null);
  return c;
}

const joinsAndLeaves = (records: readonly TickInputRecord[], playerId: number): Array<[number, string]> =>
  records.flatMap((r) => [...r.joins.filter((j) => j.playerId === playerId).map((): [number, string] => [r.tick, 'join']), ...r.leaves.filter((l) => l === playerId).map((): [number, string] => [r.tick, 'leave'])]);

describe('resume tokens (in-process server)', () => {
  it('takes a dropped player back: same player id and character body, no join or leave recorded, and the log replays exactly', async () => {
    const dir = join(tmp, 'exact');
    // A built-in scenario, so the replay (which looks scenarios up by name) can rebuild it.
    h = await startHarness({ scenarios: listScenarios().filter((d) => d.name === 'character-course'), recordDir: dir });
    const a = await h.join('ann');
    const b = await h.join('bob');
    const walk = { ...NEUTRAL_INPUT, moveX: 127, yaw: 16000, pitch: 2000 };
    drive(h, a, walk, 40);
    const bodyBefore = h.room().sim.characters().find((c) => c.playerId === a.playerId)!.bodyId;
    const token = a.welcome!.resumeToken!;
    expect(token).toMatch(/^[A-Za-z0-9_-]{43}$/);
    expect(a.welcome).toMatchObject({ resumed: false, resumeGraceMs: 30_000 });

    const dropAt = h.room().sim.tick;
    a.drop();
    h.ticks(90); // 1.5 s without a link, well inside the 30 s window
    const held = h.room().sim.characters().find((c) => c.playerId === a.playerId)!;
    expect(Math.hypot(held.velocity.x, held.velocity.z)).toBeLessThan(0.01); // it stands still while held
    expect(h.room().heldCount).toBe(1);

    const back = await resume(h, 'ann', token);
    expect(back.welcome).toMatchObject({ playerId: a.playerId, resumed: true, roomId: 'default' });
    expect(back.welcome!.resumeToken).not.toBe(token);
    expect(back.ofType('error')).toEqual([]);
    expect(h.room().sim.characters().find((c) => c.playerId === a.playerId)!.bodyId).toBe(bodyBefore);
    expect(h.room().heldCount).toBe(0);
    drive(h, back, { ...NEUTRAL_INPUT, moveX: -127 }, 30);
    h.ticks(5);
    // The returning client sees its own character in snapshots, and the observer saw no one leave or join.
    await h.settle(() => back.frames.length > 0); // with a durable recording a tick's snapshot leaves once the tick is on disk
    expect(Array.from(back.latestFrame().playerIds)).toContain(a.playerId);
    expect(b.events.filter((e) => e.type === 'playerLeft' || (e.type === 'playerJoined' && e.playerId === a.playerId && e.tick > 0))).toEqual([]);

    const { records } = h.history();
    expect(joinsAndLeaves(records, a.playerId)).toEqual([[records.find((r) => r.joins.some((j) => j.playerId === a.playerId))!.tick, 'join']]);
    // While held, the player's record carries the held input: no movement or buttons, the last look direction.
    const heldCommands = records.filter((r) => r.tick > dropAt && r.tick < dropAt + 85).map((r) => r.commands.find((c) => c.playerId === a.playerId)!.input);
    expect(heldCommands).toHaveLength(84);
    expect(new Set(heldCommands.map((c) => JSON.stringify(c)))).toEqual(new Set([JSON.stringify({ moveX: 0, moveZ: 0, yaw: 16000, pitch: 2000, buttons: 0 })]));

    const finalTick = h.room().sim.tick;
    await h.close();
    h = null;
    const report = await replayLog(join(dir, readdirSync(dir).filter((f) => f.endsWith('.taoslog'))[0]));
    expect(report.status).toBe('ok');
    expect(report.ticks).toBe(finalTick);
  });

  it('refuses a token used twice or after the grace window with the reason, and joins that client as a new player', async () => {
    h = await startHarness({ scenarios: [stripScenario], resumeGraceMs: 2000 });
    const a = await h.join('ann');
    const token = a.welcome!.resumeToken!;
    a.drop();
    h.ticks(10);
    const first = await resume(h, 'ann', token);
    expect(first.welcome).toMatchObject({ playerId: a.playerId, resumed: true });

    const again = await resume(h, 'eve', token);
    expect(again.ofType('error')).toEqual([expect.objectContaining({ code: ErrorCode.ResumeRefused, message: expect.stringMatching(/already used.*joining as a new player/) })]);
    expect(again.welcome).toMatchObject({ resumed: false });
    expect(again.welcome!.playerId).not.toBe(a.playerId);
    expect(first.closed).toBeNull(); // the refused attempt took nothing from the rightful holder

    const second = first.welcome!.resumeToken!;
    first.drop();
    h.ticks(10);
    h.clock.advance(2000); // the window ends: the held player leaves in an ordinary leave record
    h.ticks(2);
    const { records } = h.history();
    const leaves = joinsAndLeaves(records, a.playerId).filter(([, what]) => what === 'leave');
    expect(leaves).toHaveLength(1);
    expect(again.events).toContainEqual(expect.objectContaining({ type: 'playerLeft', playerId: a.playerId, tick: leaves[0][0] }));
    expect(h.room().hasPlayer(a.playerId)).toBe(false);

    const late = await resume(h, 'ann', second);
    expect(late.ofType('error')[0]?.message).toMatch(/expired: the 2 s grace window ended/);
    expect(late.welcome).toMatchObject({ resumed: false });
    expect(late.welcome!.playerId).not.toBe(a.playerId);
    expect(await h.server.metrics.registry.getSingleMetricAsString('taos_access_refused_total')).toContain('reason="resume-refused"} 2');
  });

  it('hands a still-connected player to the new connection and tells the old one it was replaced', async () => {
    h = await startHarness({ scenarios: [stripScenario] });
    const a = await h.join('ann');
    const c = await resume(h, 'ann', a.welcome!.resumeToken!);
    h.ticks(2);
    expect(c.welcome).toMatchObject({ playerId: a.playerId, resumed: true });
    expect(a.ofType('bye')).toEqual([expect.objectContaining({ reason: ByeReason.Replaced })]);
    expect(a.closed).not.toBeNull();
    expect(joinsAndLeaves(h.history().records, a.playerId).filter(([, w]) => w === 'leave')).toEqual([]);
    expect(h.room().clientCount).toBe(1);
    expect(await h.server.metrics.registry.getSingleMetricAsString('taos_resumes_total')).toMatch(/taos_resumes_total 1$/m);
  });

  it('lets a player that says bye leave at once, and voids its token', async () => {
    h = await startHarness({ scenarios: [stripScenario] });
    const a = await h.join('ann');
    const b = await h.join('bob');
    a.send({ type: 'bye' });
    h.ticks(2);
    expect(b.events).toContainEqual(expect.objectContaining({ type: 'playerLeft', playerId: a.playerId }));
    const c = await resume(h, 'ann', a.welcome!.resumeToken!);
    expect(c.ofType('error')[0]?.message).toMatch(/void: the player left the room/);
    expect(c.welcome!.playerId).not.toBe(a.playerId);
  });

  it('voids the tokens of a room that closes', async () => {
    h = await startHarness({ scenarios: [stripScenario, emptyScenario] });
    const a = await h.join('ann', 'test-empty');
    a.drop();
    h.ticks(2);
    await h.server.rooms.get('test-empty')!.close('test closes it');
    const c = await resume(h, 'ann', a.welcome!.resumeToken!);
    expect(c.ofType('error')[0]?.message).toMatch(/room has closed/);
  });

  it('refuses a token for another room than the hello names, without using it up', async () => {
    h = await startHarness({ scenarios: [stripScenario, emptyScenario] });
    const a = await h.join('ann');
    a.drop();
    h.ticks(2);
    const wrong = await resume(h, 'ann', a.welcome!.resumeToken!, 'test-empty');
    expect(wrong.ofType('error')[0]?.message).toMatch(/for room "default", not "test-empty"/);
    expect(wrong.welcome?.roomId).toBe('test-empty');
    const right = await resume(h, 'ann', a.welcome!.resumeToken!, 'default');
    expect(right.welcome).toMatchObject({ playerId: a.playerId, resumed: true });
  });

  it('lets a dropped player leave at once and sends no token when resume is off', async () => {
    h = await startHarness({ scenarios: [stripScenario], resumeGraceMs: 0 });
    const a = await h.join('ann');
    const b = await h.join('bob');
    expect(a.welcome).toMatchObject({ resumeToken: null, resumeGraceMs: 0 });
    a.drop();
    h.ticks(2);
    expect(b.events).toContainEqual(expect.objectContaining({ type: 'playerLeft', playerId: a.playerId }));
    const c = h.connect();
    c.hello('ann', null, { resumeToken: 'x'.repeat(43) });
    await h.settle(() => c.welcome !== null);
    expect(c.ofType('error')[0]).toMatchObject({ code: ErrorCode.ResumeRefused, message: expect.stringMatching(/does not resume players/) });
  });
});
