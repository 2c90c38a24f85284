// What a scenario module is written with, shared by the `taos-physics` and `taos-physics/sim` entries:
// defineScenario, deterministic maths, collision layers, input buttons and the types of the scenario contract.
export { DEFAULT_GOLDEN, defineScenario, isDefinedScenario, type DefinedScenario, type ScenarioInput } from '../shared/sim/define-scenario.ts';
export type { ParamSpec, ParamValues, PlayerRules, Rgb, ScenarioContext, ScenarioDefinition, ScenarioInstance, SpawnOptions } from '../shared/sim/scenario.ts';
export { detAtan2, detCos, detSin, quatFromAxisAngle, quatFromYaw, wrapAngle } from '../shared/sim/det-math.ts';
export { Button, type InputCommand } from '../shared/sim/input.ts';
export type { CharacterState, PlayerCommand, SimEvent, TickInputRecord } from '../shared/sim/types.ts';
export { CollisionLayer, type BodyHandle, type BodyOptions, type MotionKind, type QuatLike, type ShapeSpec, type Vec3Like } from '../shared/physics/index.ts';
export type { GameInputFieldSpec, GameInputValues } from '../shared/sim/game-input.ts';
export type { GameStateFieldSpec, GameStateValues } from '../shared/sim/game-state.ts';
export type { GameMessageEvent, GameMessageSpec } from '../shared/sim/game-messages.ts';
