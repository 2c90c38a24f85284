// Determinism cost on the 1000-body pile: the 64-bit state hash per tick, and checkpoint save/restore in the fast
// (WASM-heap) and byte (disk) forms, each next to the raw Jolt step of the same ticks for scale.
import type { FigureImpl, FigureOutput } from '../lib/figure.ts';
import { rawStepBatch } from '../lib/raw-step.ts';
import { createSceneSim, movingBodyCount, PILE_READY_TICK, PILE_SCENE, stepEmptyTo } from '../lib/scenes.ts';
import { alternate, ratio, round, roundSummary, summarize, timeMs } from '../lib/stats.ts';
import { emptyTickInput } from '../../shared/sim/types.ts';

/** Ticks stepped (untimed) between a save and the restore that rolls them back. */
const ROLLBACK_TICKS = 4;
/** Ticks per raw-step batch. */
const HASH_BATCH_TICKS = 10;

async function run(opts: { quick: boolean; log(m: string): void }): Promise<FigureOutput> {
  const hashTicks = opts.quick ? 60 : 240;
  const checkpointRounds = opts.quick ? 6 : 24;
  opts.log(`building ${PILE_SCENE.label} to tick ${PILE_READY_TICK}`);
  const sim = await createSceneSim(PILE_SCENE);
  try {
    stepEmptyTo(sim, PILE_READY_TICK);
    const bodies = movingBodyCount(sim);
    const step = (): void => void sim.step(emptyTickInput(sim.tick));

    // Hash: each sample is the first stateHash() after a tick (the cache is cold). The raw step of the same ticks is
    // timed in batches just before them (rawStepBatch rolls the world back), for scale.
    const hashMs: number[] = [];
    const rawStepMs: number[] = [];
    opts.log(`hash: ${hashTicks} ticks`);
    for (let done = 0; done < hashTicks; done += HASH_BATCH_TICKS) {
      rawStepMs.push(...rawStepBatch(sim, HASH_BATCH_TICKS));
      for (let i = 0; i < HASH_BATCH_TICKS; i++) {
        step();
        hashMs.push(timeMs(() => void sim.stateHash()));
      }
    }

    const fastSave: number[] = [];
    const fastRestore: number[] = [];
    const byteSave: number[] = [];
    const byteRestore: number[] = [];
    let byteSize = 0;
    opts.log(`checkpoints: ${checkpointRounds} rounds of each form`);
    await alternate(
      checkpointRounds,
      () => {
        let cp: ReturnType<typeof sim.saveCheckpoint> | undefined;
        fastSave.push(timeMs(() => (cp = sim.saveCheckpoint())));
        for (let k = 0; k < ROLLBACK_TICKS; k++) step();
        fastRestore.push(timeMs(() => sim.restoreCheckpoint(cp!)));
        cp!.dispose();
        for (let k = 0; k < ROLLBACK_TICKS; k++) step();
      },
      () => {
        let bytes: Uint8Array = new Uint8Array(0);
        byteSave.push(timeMs(() => (bytes = sim.saveCheckpointBytes())));
        byteSize = bytes.length;
        for (let k = 0; k < ROLLBACK_TICKS; k++) step();
        byteRestore.push(timeMs(() => sim.restoreCheckpointBytes(bytes)));
        for (let k = 0; k < ROLLBACK_TICKS; k++) step();
      },
    );

    const hash = summarize(hashMs);
    const raw = summarize(rawStepMs);
    const fs = summarize(fastSave);
    const fr = summarize(fastRestore);
    const bs = summarize(byteSave);
    const br = summarize(byteRestore);
    const label = `${bodies} moving bodies`;
    return {
      headline: {
        hashMsPerTick1000: round(hash.median, 4),
        checkpointSaveMs1000: round(fs.median, 3),
        checkpointRestoreMs1000: round(fr.median, 3),
      },
      detail: {
        scene: PILE_SCENE,
        tick: PILE_READY_TICK,
        bodies,
        hashMs: roundSummary(hash),
        rawStepMs: roundSummary(raw),
        hashShareOfRawStep: round(ratio(hash.median, raw.median) ?? NaN, 4),
        fastCheckpoint: { saveMs: roundSummary(fs), restoreMs: roundSummary(fr) },
        byteCheckpoint: { saveMs: roundSummary(bs), restoreMs: roundSummary(br), sizeBytes: byteSize },
        rollbackTicks: ROLLBACK_TICKS,
      },
      rows: [
        { figure: 'determinism cost', measure: `state hash per tick (${label}, median)`, value: hash.median, unit: 'ms', digits: 3 },
        { figure: 'determinism cost', measure: 'state hash / raw step (median)', value: ratio(hash.median, raw.median), unit: '×', digits: 3 },
        { figure: 'determinism cost', measure: `checkpoint save, fast form (${label}, median)`, value: fs.median, unit: 'ms', digits: 2 },
        { figure: 'determinism cost', measure: `checkpoint restore, fast form (median)`, value: fr.median, unit: 'ms', digits: 2 },
        { figure: 'determinism cost', measure: `checkpoint save, byte form (${Math.round(byteSize / 1024)} KiB, median)`, value: bs.median, unit: 'ms', digits: 1 },
        { figure: 'determinism cost', measure: 'checkpoint restore, byte form (median)', value: br.median, unit: 'ms', digits: 1 },
      ],
      charts: [
        {
          title: `Determinism cost, ${label} (median ms)`,
          unit: 'ms (log)',
          log: true,
          bars: [
            { label: 'raw Jolt step (floor of a tick)', value: raw.median, series: 'raw' },
            { label: 'state hash', value: hash.median, series: 'ours' },
            { label: 'checkpoint save (fast)', value: fs.median, series: 'ours' },
            { label: 'checkpoint restore (fast)', value: fr.median, series: 'ours' },
            { label: 'checkpoint save (bytes)', value: bs.median, series: 'other' },
            { label: 'checkpoint restore (bytes)', value: br.median, series: 'other' },
          ],
        },
      ],
      notes: [
        `${label} of ${PILE_SCENE.label} from tick ${PILE_READY_TICK}; hash samples are the first stateHash() after each tick (no cache).`,
        `Restores roll back ${ROLLBACK_TICKS} ticks (bodies moved since the save), alternating fast and byte rounds.`,
      ],
    };
  } finally {
    sim.destroy();
  }
}

/** The determinism-cost figure. */
export const figure: FigureImpl = { run };
