// The move policy on made-up loads: a room measured far above its estimate on a worker whose other rooms miss their
// budget moves to a worker with headroom or an idle one, else its light neighbours move away; nothing moves otherwise.
import { describe, expect, it } from 'vitest';
import { planMove, provedHeavier, type PolicyRoom, type PolicyWorker } from '../../../server/workers/move-policy.ts';

const BUDGET_MS = 12.5;

const room = (id: string, costMs: number, estimateMs: number, missingBudget = false, measured = true): PolicyRoom => ({ id, costMs, estimateMs, measured, missingBudget });
const worker = (index: number, ...rooms: PolicyRoom[]): PolicyWorker => ({ worker: index, rooms });

describe('move-policy', () => {
  it('moves the room that proved heavier than estimated to the worker with the most headroom when its neighbours miss their budget', () => {
    const workers = [worker(0, room('heavy', 11, 2), room('light-a', 1, 1, true), room('light-b', 1.5, 1.5, true)), worker(1, room('w1', 4, 4)), worker(2, room('w2', 1, 1))];
    expect(planMove(workers, BUDGET_MS)).toMatchObject({ room: 'heavy', from: 0, to: 2 });
  });

  it('moves the heavy room to an idle worker when no busy worker has room for it', () => {
    const workers = [worker(0, room('heavy', 20, 2), room('light', 1, 1, true)), worker(1, room('w1', 10, 10)), worker(2)];
    expect(planMove(workers, BUDGET_MS)).toMatchObject({ room: 'heavy', from: 0, to: 2 });
  });

  it('moves the light neighbours away when no worker can take the heavy room', () => {
    const workers = [worker(0, room('heavy', 20, 2), room('small', 0.5, 0.5, true), room('bigger', 2, 2, true)), worker(1, room('w1', 9, 9))];
    expect(planMove(workers, BUDGET_MS)).toMatchObject({ room: 'bigger', from: 0, to: 1 });
    // The next look, once `bigger` moved (and sits in the cooldown), takes the other one.
    const after = [worker(0, room('heavy', 20, 2), room('small', 0.5, 0.5, true)), worker(1, room('w1', 9, 9), room('bigger', 2, 2))];
    expect(planMove(after, BUDGET_MS, new Set(['bigger']))).toMatchObject({ room: 'small', from: 0, to: 1 });
  });

  it('leaves everything where it is when the neighbours keep their budget, the worker is within it, or nothing fits', () => {
    expect(planMove([worker(0, room('heavy', 12, 2), room('light', 1, 1)), worker(1)], BUDGET_MS)).toBeNull();
    expect(planMove([worker(0, room('heavy', 8, 2), room('light', 1, 1, true)), worker(1)], BUDGET_MS)).toBeNull();
    expect(planMove([worker(0, room('heavy', 20, 2), room('light', 1, 1, true)), worker(1, room('full', 12, 12))], BUDGET_MS)).toBeNull();
    // Alone on its worker, a heavy room slows only itself.
    expect(planMove([worker(0, room('heavy', 30, 2)), worker(1)], BUDGET_MS)).toBeNull();
  });

  it('counts only measured rooms well above their estimate as heavier, and keeps rooms moved lately where they are', () => {
    expect(provedHeavier(room('r', 11, 2))).toBe(true);
    expect(provedHeavier(room('r', 11, 2, false, false))).toBe(false);
    expect(provedHeavier(room('r', 3.5, 2))).toBe(false); // under twice its estimate
    expect(provedHeavier(room('r', 0.5, 0.2))).toBe(false); // twice, but less than a millisecond above
    // An overloaded worker of rooms as heavy as estimated is a placement matter, not a move.
    expect(planMove([worker(0, room('a', 7, 7, true), room('b', 7, 7, true)), worker(1)], BUDGET_MS)).toBeNull();
    const workers = [worker(0, room('heavy', 11, 2), room('light', 2, 2, true)), worker(1)];
    expect(planMove(workers, BUDGET_MS, new Set(['heavy']))).toBeNull();
  });

  it('picks the same move whatever order the workers and rooms come in', () => {
    const a = [worker(1, room('x', 1, 1)), worker(0, room('light', 1, 1, true), room('h2', 9, 2), room('h1', 9, 2)), worker(2, room('y', 1, 1))];
    const b = [worker(2, room('y', 1, 1)), worker(0, room('h1', 9, 2), room('h2', 9, 2), room('light', 1, 1, true)), worker(1, room('x', 1, 1))];
    expect(planMove(a, BUDGET_MS)).toEqual(planMove(b, BUDGET_MS));
    expect(planMove(a, BUDGET_MS)).toMatchObject({ room: 'h1', to: 1 });
  });
});
