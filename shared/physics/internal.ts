// The physics wrapper's internal surface for shared/sim (checkpoints save and restore body-id allocation, sensor
// overlaps and characters; the tick drains sensor transitions). Not public API: index.ts does not re-export it, and
// the lint lets only shared/physics and shared/sim import it.
export { recreateCharacter } from './character-controller.ts';
export { worldInternals, type WorldInternals } from './physics-world.ts';
