// Tests of the game API's wire form: game input values in input commands (checked like every client field) and the
// welcome's game schema (round trip, and a clear refusal of a malformed one).
import { describe, expect, it } from 'vitest';
import { ClientOpcode, decodeClientMessage, decodeServerMessage, encodeClientMessage, encodeServerMessage, packValue, unpackFrame } from '../../../shared/protocol/index.ts';
import { NEUTRAL_INPUT } from '../../../shared/sim/input.ts';
import { sampleWelcome } from './sample-messages.ts';

const withGame = {
  ...sampleWelcome,
  scenario: {
    ...sampleWelcome.scenario,
    game: {
      input: [{ name: 'kick', min: 0, max: 1 }, { name: 'power', min: -10, max: 10 }],
      state: [{ name: 'phase', kind: 'string' as const, maxLength: 12 }, { name: 'score', kind: 'number' as const, maxLength: 0 }],
      messages: [{ name: 'pickTeam', fields: [{ name: 'team', min: 0, max: 3 }] }, { name: 'ready', fields: [] }],
    },
  },
};

describe('game-schema-codec', () => {
  it('carries game input values in an input command and reads them back as canonical integers', () => {
    const r = decodeClientMessage(encodeClientMessage({ type: 'input', firstTick: 9, commands: [{ ...NEUTRAL_INPUT, game: [1, -0.3, 2.5] }] }));
    if (!r.ok || r.message.type !== 'input') throw new Error(`refused: ${JSON.stringify(r)}`);
    expect(r.message.commands[0].game).toEqual([1, 0, 3]);
    expect(Object.is(r.message.commands[0].game![1], 0)).toBe(true);
    expect(r.clampedCommands).toBe(1);
  });

  it('sends a command without game values in the five-element form', () => {
    expect(encodeClientMessage({ type: 'input', firstTick: 1, commands: [NEUTRAL_INPUT] })).toEqual(packValue([2, 1, [[0, 0, 0, 0, 0]]]));
  });

  it('refuses malformed game values as bad-input naming the command and the value', () => {
    const frame = (game: unknown): ReturnType<typeof decodeClientMessage> => decodeClientMessage(packValue([2, 4, [[0, 0, 0, 0, 0, game]]]));
    expect(frame('x')).toMatchObject({ ok: false, code: 'bad-input', error: 'input.commands[0] (tick 4): game must be an array of numbers, got "x"' });
    expect(frame([1, 'a'])).toMatchObject({ ok: false, code: 'bad-input', error: 'input.commands[0] (tick 4): game[1] must be a number, got "a"' });
    expect(frame(new Array(17).fill(0))).toMatchObject({ ok: false, error: 'input.commands[0] (tick 4): game must have at most 16 values, got 17' });
    expect(frame([Number.POSITIVE_INFINITY])).toMatchObject({ ok: false, error: 'input.commands[0] (tick 4): game[0] must be finite, got Infinity' });
    expect(decodeClientMessage(packValue([2, 4, [[0, 0, 0, 0, 0, [], 1]]]))).toMatchObject({ ok: false, code: 'bad-input' });
  });

  it('round-trips a welcome with a game schema and leaves the key out without one', () => {
    const back = decodeServerMessage(encodeServerMessage(withGame));
    expect(back).toEqual({ ok: true, message: withGame });
    const plain = decodeServerMessage(encodeServerMessage(sampleWelcome));
    expect(plain.ok && plain.message.type === 'welcome' && 'game' in plain.message.scenario).toBe(false);
  });

  it('refuses a welcome whose game input rows are malformed or unsorted', () => {
    const decode = (input: unknown): string => {
      const [op, map] = unpackFrame(encodeServerMessage(sampleWelcome)) as [number, { scenario: Record<string, unknown> }];
      map.scenario.input = input;
      const r = decodeServerMessage(packValue([op, map]));
      return r.ok ? 'ok' : r.error;
    };
    expect(decode([['b', 0, 1], ['a', 0, 1]])).toMatch(/welcome\.scenario\.input must be sorted by name/);
    expect(decode([['a', 1, 1]])).toMatch(/welcome\.scenario\.input\[0\] must be \[name, min, max\]/);
    expect(decode('nope')).toMatch(/welcome\.scenario\.input must be an array/);
  });

  it('carries game state values with a snapshot only when given', () => {
    const bytes = new Uint8Array([1, 2, 3]);
    const back = decodeServerMessage(encodeServerMessage({ type: 'snapshot', bytes, descriptors: [], state: ['play', 3.5] }));
    expect(back).toEqual({ ok: true, message: { type: 'snapshot', bytes, descriptors: [], state: ['play', 3.5] } });
    // Without state (or descriptors) the snapshot travels raw: its opcode byte, then the snapshot bytes.
    expect(encodeServerMessage({ type: 'snapshot', bytes, descriptors: [] })).toEqual(new Uint8Array([18, 1, 2, 3]));
    expect(decodeServerMessage(new Uint8Array([18, 1, 2, 3]))).toEqual({ ok: true, message: { type: 'snapshot', bytes, descriptors: [] } });
  });

  it('refuses snapshot state values that are neither finite numbers nor short strings', () => {
    const decode = (state: unknown): string => {
      const r = decodeServerMessage(packValue([18, new Uint8Array([1]), null, state]));
      return r.ok ? 'ok' : r.error;
    };
    expect(decode([{}])).toMatch(/snapshot\.state \[0\] must be a finite number or a string of at most 64 characters, got an object/);
    expect(decode(['x'.repeat(65)])).toMatch(/at most 64 characters/);
    expect(decode(new Array(33).fill(0))).toMatch(/at most 32 values/);
    expect(decode([1, 'a'])).toBe('ok');
  });

  it('refuses a welcome whose state rows are malformed', () => {
    const decode = (state: unknown): string => {
      const [op, map] = unpackFrame(encodeServerMessage(sampleWelcome)) as [number, { scenario: Record<string, unknown> }];
      map.scenario.state = state;
      const r = decodeServerMessage(packValue([op, map]));
      return r.ok ? 'ok' : r.error;
    };
    expect(decode([['a', 'string', 65]])).toMatch(/welcome\.scenario\.state\[0\] must be \[name, 'number', 0\] or \[name, 'string', maxLength\]/);
    expect(decode([['a', 'bool', 0]])).toMatch(/must be \[name, 'number', 0\]/);
    expect(decode([['a', 'number', 0]])).toBe('ok');
  });

  it('carries a game message and refuses a malformed one as bad-message', () => {
    expect(decodeClientMessage(encodeClientMessage({ type: 'game', name: 'pickTeam', payload: [2] }))).toEqual({ ok: true, message: { type: 'game', name: 'pickTeam', payload: [2] }, clampedCommands: 0 });
    const refuse = (frame: unknown[]): string => {
      const r = decodeClientMessage(packValue(frame));
      return r.ok ? 'ok' : `${r.code}: ${r.error}`;
    };
    expect(refuse([ClientOpcode.GameMessage, 'pick team', []])).toBe('bad-message: game.name must be an identifier of 1-32 characters, got "pick team"');
    expect(refuse([ClientOpcode.GameMessage, 'pick', [0.5]])).toBe('bad-message: game.payload[0] must be an integer within ±1000000, got 0.5');
    expect(refuse([ClientOpcode.GameMessage, 'pick', new Array(9).fill(0)])).toBe('bad-message: game.payload must be an array of at most 8 integers');
    expect(refuse([ClientOpcode.GameMessage, 'pick'])).toBe('bad-message: game must have 2 field(s), got 1');
    // A predicting client names the tick its own simulation applies the message on.
    expect(decodeClientMessage(encodeClientMessage({ type: 'game', name: 'ready', payload: [], tick: 1234 }))).toEqual({ ok: true, message: { type: 'game', name: 'ready', payload: [], tick: 1234 }, clampedCommands: 0 });
    expect(refuse([ClientOpcode.GameMessage, 'pick', [], -1])).toBe('bad-message: game.tick must be an integer tick in [0, 4294967295], got -1');
    expect(refuse([ClientOpcode.GameMessage, 'pick', [], 1.5])).toMatch(/^bad-message: game.tick must be an integer tick/);
    expect(refuse([ClientOpcode.GameMessage, 'pick', [], 'now'])).toMatch(/^bad-message: game.tick must be an integer tick/);
    expect(refuse([ClientOpcode.GameMessage, 'pick', [], 1, 2])).toBe('bad-message: game must have 2 field(s), got 4');
  });

  it('refuses a welcome whose message rows are malformed', () => {
    const decode = (messages: unknown): string => {
      const [op, map] = unpackFrame(encodeServerMessage(sampleWelcome)) as [number, { scenario: Record<string, unknown> }];
      map.scenario.messages = messages;
      const r = decodeServerMessage(packValue([op, map]));
      return r.ok ? 'ok' : r.error;
    };
    expect(decode([['pick', [['b', 0, 1], ['a', 0, 1]]]])).toMatch(/welcome\.scenario\.messages\[0\] fields must be sorted/);
    expect(decode([['pick', [['a', 2, 1]]]])).toMatch(/field 0 must be \[name, min, max\]/);
    expect(decode([['pick', []]])).toBe('ok');
  });
});
