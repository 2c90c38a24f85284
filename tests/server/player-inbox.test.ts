// Tests for server/player-inbox.ts: snapshot acks work the same whether they ride on input messages (protocol 7) or
// come alone, and an ack on an input message whose commands are refused still counts.
import { afterEach, describe, expect, it } from 'vitest';
import { ErrorCode, readSnapshotHeader } from '../../shared/protocol/index.ts';
import { NEUTRAL_INPUT, type InputCommand } from '../../shared/sim/input.ts';
import { startHarness, type Harness, type TestClient } from './harness.ts';
import { stripScenario } from './test-scenarios.ts';

let h: Harness | null = null;
afterEach(async () => {
  await h?.close();
  h = null;
});

const walk = (moveX: number): InputCommand => ({ ...NEUTRAL_INPUT, moveX });
/** How many ticks each snapshot's baseline lags behind it (null: a full snapshot). */
const baselineAges = (c: TestClient): Array<number | null> => {
  let previousTick: number | null = null;
  return c.ofType('snapshot').map((s) => {
    // A delta carries the low bits of its tick, completed from the snapshot before it.
    const header = readSnapshotHeader(s.bytes, previousTick);
    previousTick = header.tick;
    return header.baselineTick === null ? null : header.tick - header.baselineTick;
  });
};

describe('PlayerInbox', () => {
  it('takes an ack riding on an input message as an ack: deltas against it follow, and no ack message is needed', async () => {
    h = await startHarness({ scenarios: [stripScenario], snapshotRateHz: 60 });
    const c = await h.join('ann');
    c.autoAck = false;
    for (let i = 0; i < 20; i++) {
      const newest = c.frames.at(-1)?.tick;
      c.send({ type: 'input', firstTick: h.room().sim.tick + 2, commands: [walk(60)], ...(newest === undefined ? {} : { ackTick: newest }) });
      h.ticks(1);
    }
    const ages = baselineAges(c);
    expect(ages.length).toBeGreaterThanOrEqual(20);
    // Every snapshot is a delta against the snapshot acked on the last input message: one or two ticks old.
    expect(ages.slice(4).every((age) => age !== null && age <= 2)).toBe(true);
    expect(c.ofType('error')).toEqual([]);
  });

  it('still takes acks that come alone, and an ack on an input message whose commands are refused', async () => {
    h = await startHarness({ scenarios: [stripScenario], snapshotRateHz: 60 });
    const alone = await h.join('alone');
    const refused = await h.join('refused');
    refused.autoAck = false;
    h.ticks(10); // no acks: full snapshots, or deltas against a baseline that falls behind
    const before = baselineAges(refused).at(-1);
    expect(before === null || before! > 5).toBe(true);
    for (let i = 0; i < 6; i++) {
      // Game input values in a scene without game input fields: the message's commands are refused (bad-input), its
      // ack still counts. Six refusals stay under the bad-message burst.
      refused.send({ type: 'input', firstTick: h.room().sim.tick + 2, commands: [{ ...walk(0), game: [1] }], ackTick: refused.frames.at(-1)!.tick });
      h.ticks(1);
    }
    expect(baselineAges(alone).slice(4).every((age) => age !== null && age <= 2)).toBe(true);
    expect(baselineAges(refused).slice(-3).every((age) => age !== null && age <= 2)).toBe(true);
    expect(refused.ofType('error').map((e) => e.code)).toContain(ErrorCode.BadInput);
  });
});
