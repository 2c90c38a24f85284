// Tests of the predicting client's own game messages: each goes on the first predicted tick at or after the one it
// was sent for (at most 8 a tick), leaves when a confirmed record carries it, moves to a later tick when the server
// applied it later, and is dropped when never confirmed.
import { describe, expect, it } from 'vitest';
import { OwnMessages } from '../../../sdk/prediction/own-messages.ts';

const ME = 3;

describe('own-messages', () => {
  it('puts a message on the first predicted tick at or after the one it was sent for, and keeps it there on re-simulation', () => {
    const own = new OwnMessages(ME, 60);
    own.add('ready', [], 10);
    expect(own.forTick(9)).toEqual([]);
    expect(own.forTick(10)).toEqual([{ playerId: ME, name: 'ready', payload: [] }]);
    expect(own.forTick(11)).toEqual([]);
    // A rollback re-simulates tick 10: the message is applied there again, once.
    expect(own.forTick(10)).toEqual([{ playerId: ME, name: 'ready', payload: [] }]);
  });

  it('spreads more than 8 messages over later ticks, in send order', () => {
    const own = new OwnMessages(ME, 60);
    for (let i = 0; i < 10; i++) own.add('pick', [i], 5);
    expect(own.forTick(5).map((m) => m.payload[0])).toEqual([0, 1, 2, 3, 4, 5, 6, 7]);
    expect(own.forTick(6).map((m) => m.payload[0])).toEqual([8, 9]);
  });

  it('forgets the oldest messages a confirmed record carries, whatever tick they were predicted on', () => {
    const own = new OwnMessages(ME, 60);
    own.add('a', [], 10);
    own.add('b', [], 12);
    own.forTick(10);
    own.forTick(12);
    // The server applied "a" a tick early; another player's message does not count.
    own.confirmed(9, [{ playerId: 1, name: 'x', payload: [] }, { playerId: ME, name: 'a', payload: [] }]);
    expect(own.size).toBe(1);
    expect(own.forTick(10)).toEqual([]);
    expect(own.forTick(12)).toEqual([{ playerId: ME, name: 'b', payload: [] }]);
  });

  it('moves a message the server has not applied by its predicted tick to the next one, and drops it when long overdue', () => {
    const own = new OwnMessages(ME, 5);
    own.add('late', [], 20);
    own.forTick(20);
    own.confirmed(20, undefined);
    expect(own.forTick(20)).toEqual([]);
    expect(own.forTick(21)).toEqual([{ playerId: ME, name: 'late', payload: [] }]);
    for (let t = 21; t <= 25; t++) {
      own.confirmed(t, undefined);
      own.forTick(t + 1);
    }
    expect(own.size).toBe(1);
    own.confirmed(26, undefined);
    expect(own.size).toBe(0);
    expect(own.forTick(27)).toEqual([]);
  });
});
