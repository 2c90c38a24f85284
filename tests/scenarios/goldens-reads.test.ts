// Reading only the bodies that can have moved gives the very state a read of every body gives, and the state hash
// streamed from the simulation is the hash of its full dump: over every registered scenario's golden run, all agree
// on every tick (also with reads skipped between hashes) and end on the stored golden hash.
import { readFileSync } from 'node:fs';
import { fileURLToPath } from 'node:url';
import { describe, expect, it } from 'vitest';
import '../../server/physics-node.ts';
import { listScenarios } from '../../scenarios/index.ts';
import { worldInternals } from '../../shared/physics/internal.ts';
import { BotScript } from '../../shared/sim/bots.ts';
import { GOLDEN_JOIN_SPACING_TICKS, GOLDEN_SEED, parseGoldenFile } from '../../shared/sim/golden.ts';
import { hashDump } from '../../shared/sim/state-dump.ts';
import { Simulation } from '../../shared/sim/simulation.ts';

/** Ticks between two hashes of the simulation that skips reads (a prime, so it drifts against the scenes' rhythms). */
const SPARSE_HASH_TICKS = 7;

describe('goldens with reads of only what moved and a streamed hash', () => {
  for (const def of listScenarios()) {
    it(`${def.name}: hashes as a read of every body and as its full dump do on every tick, and ends on its golden`, async () => {
      const path = fileURLToPath(new URL(`../../scenarios/${def.name}.golden.json`, import.meta.url));
      const golden = parseGoldenFile(JSON.parse(readFileSync(path, 'utf8')), path);
      const every = await Simulation.create({ scenario: def, seed: GOLDEN_SEED });
      const moved = await Simulation.create({ scenario: def, seed: GOLDEN_SEED });
      const sparse = await Simulation.create({ scenario: def, seed: GOLDEN_SEED });
      worldInternals(every.world).setEveryBodyReads(true);
      try {
        const script = new BotScript({ seed: GOLDEN_SEED, bots: golden.bots, joinSpacingTicks: GOLDEN_JOIN_SPACING_TICKS });
        let compared = 0;
        for (let t = 0; t < golden.ticks; t++) {
          const record = script.next();
          every.step(record);
          moved.step(record);
          sparse.step(record);
          const reference = every.stateHash();
          if (hashDump(every.dumpState()) !== reference) expect.fail(`${def.name}: tick ${every.tick}: the streamed hash is not the dump's`);
          if (moved.stateHash() !== reference) expect.fail(`${def.name}: tick ${every.tick}: ${JSON.stringify(moved.firstDivergence(every))}`);
          if (every.tick % SPARSE_HASH_TICKS === 0) {
            expect(sparse.stateHash(), `${def.name}: tick ${every.tick}, reads ${SPARSE_HASH_TICKS} ticks apart`).toBe(reference);
            compared++;
          }
        }
        expect(compared).toBe(Math.floor(golden.ticks / SPARSE_HASH_TICKS));
        expect(moved.stateHash()).toBe(golden.hash);
        expect(every.stateHash()).toBe(golden.hash);
      } finally {
        every.destroy();
        moved.destroy();
        sparse.destroy();
      }
    });
  }
});
