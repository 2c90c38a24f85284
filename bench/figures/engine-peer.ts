// Engine peer (--peers): the 1000-body shape-rain pile copied body for body into Rapier (deterministic build) and
// both engines stepped from the same state at 60 Hz, alternating batches; reports each step time and the ratio.
import { BodyFlag } from '../../shared/physics/index.ts';
import type { FigureImpl, FigureOutput } from '../lib/figure.ts';
import { mirrorInRapier } from '../lib/rapier-mirror.ts';
import { createSceneSim, movingBodyCount, PILE_SCENE, stepEmptyTo } from '../lib/scenes.ts';
import { alternate, ratio, round, roundSummary, summarize } from '../lib/stats.ts';

const BATCH_TICKS = 20;
/** Where the copy is taken: drops still landing on the pile, so both engines have contacts to solve. */
const START_TICK = 280;

async function run(opts: { quick: boolean; log(m: string): void }): Promise<FigureOutput> {
  const batches = opts.quick ? 6 : 24;
  opts.log(`building ${PILE_SCENE.label} to tick ${START_TICK}`);
  const sim = await createSceneSim(PILE_SCENE);
  try {
    stepEmptyTo(sim, START_TICK);
    const bodies = movingBodyCount(sim);
    const mirror = await mirrorInRapier(sim);
    try {
      opts.log(`${mirror.bodies} bodies in Rapier; ${batches} alternating batches of ${BATCH_TICKS} ticks`);
      const jolt: number[] = [];
      const rapier: number[] = [];
      const world = sim.world;
      await alternate(
        batches,
        () => {
          for (let i = 0; i < BATCH_TICKS; i++) {
            const t0 = performance.now();
            world.stepFixed();
            jolt.push(performance.now() - t0); // stepFixed() hands back (and this drops) the step's sensor transitions
          }
        },
        () => {
          for (let i = 0; i < BATCH_TICKS; i++) {
            const t0 = performance.now();
            mirror.world.step();
            rapier.push(performance.now() - t0);
          }
        },
      );
      const read = sim.readBodyStates();
      let joltAwake = 0;
      for (let i = 0; i < read.count; i++) if ((read.flags[i] & BodyFlag.Active) !== 0) joltAwake++;
      let rapierAwake = 0;
      mirror.world.forEachRigidBody((b) => {
        if (b.isDynamic() && !b.isSleeping()) rapierAwake++;
      });
      const j = summarize(jolt);
      const r = summarize(rapier);
      const medianRatio = ratio(r.median, j.median);
      return {
        headline: {},
        detail: {
          scene: PILE_SCENE,
          startTick: START_TICK,
          ticks: batches * BATCH_TICKS,
          bodies,
          joltStepMs: roundSummary(j),
          rapierStepMs: roundSummary(r),
          rapierOverJoltMedian: medianRatio === null ? null : round(medianRatio, 3),
          rapierOverJoltMean: round(ratio(r.mean, j.mean) ?? NaN, 3),
          awakeAtEnd: { jolt: joltAwake, rapier: rapierAwake },
          skippedShapes: mirror.skipped,
        },
        rows: [
          { figure: 'engine peer', measure: `Jolt step, ${bodies}-body pile (median)`, value: j.median, unit: 'ms', digits: 2 },
          { figure: 'engine peer', measure: `Rapier (deterministic) step, same pile (median)`, value: r.median, unit: 'ms', digits: 2 },
          { figure: 'engine peer', measure: 'Rapier / Jolt (median)', value: medianRatio, unit: '×', digits: 2 },
        ],
        charts: [
          {
            title: `Engine peer: step time of the same ${bodies}-body pile (median ms)`,
            unit: 'ms',
            bars: [
              { label: 'Jolt 1.1.0 (wasm, single thread)', value: j.median, series: 'ours' },
              { label: 'Rapier 0.21 deterministic-compat', value: r.median, series: 'baseline' },
              { label: 'Jolt p99', value: j.p99, series: 'ours' },
              { label: 'Rapier p99', value: r.p99, series: 'baseline' },
            ],
          },
        ],
        notes: [
          `The pile of ${PILE_SCENE.label} at tick ${START_TICK} (drops still landing), copied into Rapier with each body's shape, pose, velocities, mass, friction (geometric mean), restitution and damping; both step ${batches * BATCH_TICKS} ticks at 1/60 s with their default solver settings, alternating ${BATCH_TICKS}-tick batches.`,
          `Awake dynamic bodies at the end: Jolt ${joltAwake}, Rapier ${rapierAwake} (sleeping rules differ, so the workloads drift apart over time).`,
          ...(mirror.skipped.length > 0 ? [`Shapes without a Rapier counterpart were skipped: ${mirror.skipped.join(', ')}.`] : []),
        ],
      };
    } finally {
      mirror.free();
    }
  } finally {
    sim.destroy();
  }
}

/** The engine-peer figure. */
export const figure: FigureImpl = { run };
