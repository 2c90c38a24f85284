// The benchmark scenes, built through the public Simulation API: the 1000-body shape-rain pile (every drop landed),
// cubes-901 with its rolling player cube, the stock 300-body rain and the crowd scene; same records every run.
import '../../server/physics-node.ts';
import { getScenario, scenarioNames } from '../../scenarios/index.ts';
import { BodyFlag } from '../../shared/physics/index.ts';
import { BotScript } from '../../shared/sim/bots.ts';
import { Simulation } from '../../shared/sim/simulation.ts';
import { emptyTickInput, type TickInputRecord } from '../../shared/sim/types.ts';

/** The 1000-body scene: shape-rain with count 1000 (4 drops per tick: all 1000 exist from tick 250). */
export const PILE_SCENE = { scenario: 'shape-rain', params: { count: 1000 }, label: 'shape-rain 1000' } as const;
/** The snapshot-bandwidth scene. */
export const CUBES_SCENE = { scenario: 'cubes-901', params: {}, label: 'cubes-901' } as const;
/** The stock ~300-body scene of the clients-per-core and rooms-per-core figures (shape-rain's default count). */
export const STOCK_SCENE = { scenario: 'shape-rain', params: { count: 300 }, label: 'shape-rain 300' } as const;
/**
 * The scene made for crowds (spawn points and ground sized to the player cap, issue 14 item 2): measured by the
 * clients-per-core figure once a scenario of this name is registered, reported as not measured until then.
 */
export const CROWD_SCENE = { scenario: 'crowd-arena', params: {}, label: 'crowd-arena' } as const;

/** A scene: a registered scenario with parameters. */
export interface Scene {
  scenario: string;
  params: Readonly<Record<string, number>>;
  label: string;
}

/** Tick at which every shape-rain drop of a 1000-body pile has landed (250 ticks of drops + 1.5 s of fall). */
export const PILE_READY_TICK = 340;

/** Whether the scene's scenario is registered. */
export function sceneAvailable(scene: Scene): boolean {
  return scenarioNames().includes(scene.scenario);
}

/** Builds a scene's Simulation (seed 1). */
export function createSceneSim(scene: Scene, seed: number | string = 1): Promise<Simulation> {
  return Simulation.create({ scenario: getScenario(scene.scenario), params: scene.params, seed });
}

/** Steps `sim` with empty records (nobody joined) until its tick counter reaches `tick`. */
export function stepEmptyTo(sim: Simulation, tick: number): void {
  while (sim.tick < tick) sim.step(emptyTickInput(sim.tick));
}

/** Records of `bots` scripted players (seed 1) that all join at tick 0; `next()` gives the record for sim.tick. */
export function botRecords(bots: number, seed: number | string = 1): { next(): TickInputRecord } {
  const script = new BotScript({ seed, bots, joinTicks: Array.from({ length: bots }, () => 0) });
  return { next: () => script.next() };
}

/** Number of non-static bodies in the simulation now. */
export function movingBodyCount(sim: Simulation): number {
  const s = sim.readBodyStates();
  let n = 0;
  for (let i = 0; i < s.count; i++) if ((s.flags[i] & BodyFlag.Static) === 0) n++;
  return n;
}
