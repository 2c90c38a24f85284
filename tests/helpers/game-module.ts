// Test helper: writes a small scenario module of a game's own ("crate-drop": crates fall on a pad) into a directory,
// the way a user would write one, importing defineScenario from wherever the test says (the repo or the package).
import { writeFile } from 'node:fs/promises';
import { join } from 'node:path';
import { pathToFileURL } from 'node:url';

/** The repository's defineScenario module, as an import specifier usable from any directory. */
export const REPO_DEFINE_SCENARIO = pathToFileURL(new URL('../../shared/sim/define-scenario.ts', import.meta.url).pathname).href;

/** Options of writeGameModule. */
export interface GameModuleOptions {
  /** Where defineScenario is imported from (default: the repository's module). */
  importFrom?: string;
  /** Crate half size in metres: another value is another version of the game. Default 0.4. */
  crateHalfMetres?: number;
  /** File name in `dir`. Default game.ts. */
  fileName?: string;
  /** Scenario name. Default crate-drop. */
  name?: string;
}

/** Writes the module and returns its path. */
export async function writeGameModule(dir: string, opts: GameModuleOptions = {}): Promise<string> {
  const path = join(dir, opts.fileName ?? 'game.ts');
  const half = opts.crateHalfMetres ?? 0.4;
  await writeFile(
    path,
    `import { defineScenario } from '${opts.importFrom ?? REPO_DEFINE_SCENARIO}';

export const scenario = defineScenario({
  name: '${opts.name ?? 'crate-drop'}',
  description: 'Crates fall on a pad',
  params: { crates: { default: 6, min: 1, max: 50, integer: true, description: 'crates dropped' } },
  bounds: { min: { x: -20, y: -5, z: -20 }, max: { x: 20, y: 30, z: 20 } },
  build(ctx) {
    ctx.spawn({ kind: 'box', halfExtents: { x: 10, y: 0.5, z: 10 } }, { x: 0, y: -0.5, z: 0 }, null, { motion: 'static' });
    let dropped = 0;
    return {
      spawnPoint: (n: number) => ({ x: n % 4, y: 0.05, z: 6 }),
      onTick(c) {
        if (dropped < c.params.crates && c.tick % 10 === 0) {
          c.spawn({ kind: 'box', halfExtents: { x: ${half}, y: ${half}, z: ${half} } }, { x: c.rng.range(-3, 3), y: 6, z: c.rng.range(-3, 3) });
          dropped++;
        }
      },
      saveState: () => [dropped],
      restoreState: (s: readonly number[]) => {
        dropped = s[0];
      },
    };
  },
});
`,
  );
  return path;
}
