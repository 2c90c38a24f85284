// Fits a client's decoded input commands to its room's game input fields before any reaches the input buffer: all
// commands of a message or none (a bad one refuses the whole message, naming the command and its tick).
import type { InputMessage } from '../shared/protocol/index.ts';
import { fitGameInput, type GameInputField } from '../shared/sim/game-input.ts';
import type { InputCommand } from '../shared/sim/input.ts';

/** The message's commands fitted to `fields` (and how many were clamped into range), or why they were refused. */
export function fitInputMessage(msg: InputMessage, fields: readonly GameInputField[]): { ok: true; commands: InputCommand[]; clamped: number } | { ok: false; error: string } {
  // The common case, a scenario without game input and commands without game values, fits as it is: nothing to copy.
  if (fields.length === 0 && msg.commands.every((c) => c.game === undefined || c.game.length === 0)) return { ok: true, commands: msg.commands, clamped: 0 };
  const commands: InputCommand[] = [];
  let clamped = 0;
  for (let i = 0; i < msg.commands.length; i++) {
    const fit = fitGameInput(msg.commands[i], fields);
    if (!fit.ok) return { ok: false, error: `input.commands[${i}] (tick ${msg.firstTick + i}): ${fit.error}` };
    if (fit.clamped) clamped++;
    commands.push(fit.command);
  }
  return { ok: true, commands, clamped };
}
