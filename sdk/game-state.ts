// The SDK's copy of a room's replicated game state: the fields the welcome names, the values the latest snapshot that
// carried state brought, and which names changed. NetClient exposes it as `gameState` with a 'gameState' event.
import type { StateFieldInfo } from '../shared/protocol/game-schema-codec.ts';
import type { GameStateValue, GameStateValues } from '../shared/sim/game-state.ts';

/** What a 'gameState' event carries: the whole state now and the names whose values changed. */
export interface GameStateChange<S extends GameStateValues = GameStateValues> {
  state: Readonly<S>;
  changed: readonly (keyof S & string)[];
}

/** The client's mirror of the room's game state. */
export class GameStateMirror {
  private fields: readonly StateFieldInfo[] = [];
  private values: GameStateValues = Object.freeze({});

  /** The current state by name (empty before the first snapshot with state). */
  get state(): GameStateValues {
    return this.values;
  }

  /** A new welcome: its fields; the state starts empty until the first snapshot brings values. */
  welcome(fields: readonly StateFieldInfo[]): void {
    this.fields = fields;
    this.values = Object.freeze({});
  }

  /**
   * Applies a snapshot's values (field order); returns the change, null when nothing changed, or an error sentence
   * when the values do not fit the welcome's fields (count or kinds).
   */
  apply(list: readonly GameStateValue[]): GameStateChange | null | string {
    if (list.length !== this.fields.length) return `snapshot game state has ${list.length} values, the welcome declared ${this.fields.length} fields`;
    const next: Record<string, GameStateValue> = {};
    const changed: string[] = [];
    for (let i = 0; i < list.length; i++) {
      const f = this.fields[i];
      const v = list[i];
      if (typeof v !== f.kind || (typeof v === 'string' && v.length > f.maxLength)) return `snapshot game state ${f.name} does not fit its declared kind ${f.kind}`;
      next[f.name] = v;
      if (!Object.hasOwn(this.values, f.name) || this.values[f.name] !== v) changed.push(f.name);
    }
    if (changed.length === 0) return null;
    this.values = Object.freeze(next);
    return { state: this.values, changed };
  }
}
