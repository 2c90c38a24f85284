// The SDK side of game-defined input: setInput({...command, kick: 1}) splits the built-in command from the scenario's
// named fields and turns the names into InputCommand.game in the order the welcome's schema gives.
import { gameInputArray, GAME_NAME_PATTERN, type GameInputField } from '../shared/sim/game-input.ts';
import { NEUTRAL_INPUT, validateInputCommand, type InputCommand } from '../shared/sim/input.ts';
import { describeValue } from '../shared/sim/describe-value.ts';

/** What setInput takes: the built-in command plus the scenario's game input fields by name (e.g. `kick: 1`). */
export type PlayerInput = Omit<InputCommand, 'game'> & { readonly [field: string]: number };

const BUILT_IN = new Set(['moveX', 'moveZ', 'yaw', 'pitch', 'buttons']);

/** Holds the player's input across connections; named game values map to fields once a welcome names them. */
export class GameInputMapper {
  private base: InputCommand = { ...NEUTRAL_INPUT };
  private named: Record<string, number> = {};
  private fields: readonly GameInputField[] | null = null;

  /** The full command to send now (game values in field order once a welcome is known). */
  get command(): InputCommand {
    if (this.fields === null || this.fields.length === 0) return this.base;
    return { ...this.base, game: gameInputArray(this.named, this.fields) };
  }

  /** The game input fields of the current scenario (empty before a welcome or when it declares none). */
  get gameFields(): readonly GameInputField[] {
    return this.fields ?? [];
  }

  /** Takes a new input; throws a clear Error for a bad built-in value, a non-number, or a name the scenario lacks. */
  set(input: InputCommand | PlayerInput): InputCommand {
    if (input === null || typeof input !== 'object') throw new Error('setInput: input must be an object');
    const named: Record<string, number> = {};
    for (const key of Object.keys(input)) {
      if (BUILT_IN.has(key)) continue;
      const value: unknown = (input as Record<string, unknown>)[key];
      if (key === 'game') {
        if (value === undefined) continue;
        throw new Error('setInput: give game input by field name ({...cmd, kick: 1}), not as a game array');
      }
      if (!GAME_NAME_PATTERN.test(key)) throw new Error(`setInput: ${describeValue(key)} is not a game input field name`);
      if (typeof value !== 'number' || !Number.isFinite(value)) throw new Error(`setInput: game input ${key} must be a finite number, got ${describeValue(value)}`);
      named[key] = value;
    }
    const v = validateInputCommand({ moveX: input.moveX, moveZ: input.moveZ, yaw: input.yaw, pitch: input.pitch, buttons: input.buttons });
    if (!v.ok) throw new Error(`setInput: ${v.error}`);
    if (this.fields !== null) gameInputArray(named, this.fields); // throws for names the scenario does not declare
    this.base = v.command;
    this.named = named;
    return this.command;
  }

  /** A welcome named the scenario's fields: returns the command to send and the names it does not declare (dropped). */
  welcome(fields: readonly GameInputField[]): { command: InputCommand; unknown: string[] } {
    this.fields = fields;
    const unknown = Object.keys(this.named).filter((k) => !fields.some((f) => f.name === k));
    for (const k of unknown) delete this.named[k];
    return { command: this.command, unknown };
  }
}
