// Checks every registered scenario against its stored golden (scenarios/<name>.golden.json): the scripted bot run
// of golden.ticks ticks must end on the stored state hash. Rewrite goldens only with `npm run goldens -- --write`.
import { existsSync, readFileSync } from 'node:fs';
import { fileURLToPath } from 'node:url';
import { describe, expect, it } from 'vitest';
import '../../server/physics-node.ts';
import { installedJoltVersion } from '../../server/log/jolt-version.ts';
import { listScenarios } from '../../scenarios/index.ts';
import { GOLDEN_SEED, parseGoldenFile, runGolden } from '../../shared/sim/golden.ts';

const FIX = 'npx taos-physics goldens --write --scenario <name> (only when the change is intended)';

describe('goldens', () => {
  it('has scenarios to check', () => {
    expect(listScenarios().length).toBeGreaterThan(0);
  });

  for (const def of listScenarios()) {
    it(`${def.name} ends its golden run on the stored hash`, async () => {
      const path = fileURLToPath(new URL(`../../scenarios/${def.name}.golden.json`, import.meta.url));
      expect(existsSync(path), `no golden for ${def.name}: ${FIX}`).toBe(true);
      const golden = parseGoldenFile(JSON.parse(readFileSync(path, 'utf8')), path);
      expect(golden.scenario).toBe(def.name);
      expect({ ticks: golden.ticks, bots: golden.bots, seed: golden.seed }, `golden script changed: ${FIX}`).toEqual({ ticks: def.golden.ticks, bots: def.golden.bots, seed: GOLDEN_SEED });
      expect(golden.joltVersion, `golden recorded with jolt-physics ${golden.joltVersion}: ${FIX}`).toBe(installedJoltVersion());
      const result = await runGolden(def);
      expect(result.hash, `${def.name} no longer reproduces its golden (hash every 60 ticks: ${JSON.stringify(result.checkpoints)}); if intended: ${FIX}`).toBe(golden.hash);
    });
  }
});
