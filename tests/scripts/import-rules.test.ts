// Tests of scripts/import-rules.ts: arrows that run the wrong way are refused with the rule named, the physics
// wrapper is entered only through its entry points, browser code never reaches the engine (through any chain of
// runtime imports), browser areas use no Node or server packages, and this repository follows its own rules.
import { readdirSync, readFileSync, statSync } from 'node:fs';
import { join, relative, sep } from 'node:path';
import { fileURLToPath } from 'node:url';
import { describe, expect, it } from 'vitest';
import { checkImports, parseImports, type SourceFile } from '../../scripts/import-rules.ts';

/** Problems as `file:line: message` for compact assertions. */
function problems(files: SourceFile[]): string[] {
  return checkImports(files).map((p) => `${p.file}:${p.line}: ${p.message}`);
}

const file = (path: string, ...lines: string[]): SourceFile => ({ path, text: `// ${path}\n${lines.join('\n')}\n` });

describe('parseImports', () => {
  it('finds static, multi-line, re-export, side-effect and dynamic imports with their lines, and skips comments', () => {
    const text = [
      "import { a } from './a.ts';",
      'import {',
      '  b,',
      "} from '../b.ts';",
      "export { c } from './c.ts';",
      "export type { D } from './d.ts';",
      "import './side.ts';",
      "// import { e } from './commented.ts';",
      "const f = await import('./f.ts');",
    ].join('\n');
    expect(parseImports(text)).toEqual([
      { specifier: './a.ts', line: 1, typeOnly: false, dynamic: false },
      { specifier: '../b.ts', line: 4, typeOnly: false, dynamic: false },
      { specifier: './c.ts', line: 5, typeOnly: false, dynamic: false },
      { specifier: './d.ts', line: 6, typeOnly: true, dynamic: false },
      { specifier: './side.ts', line: 7, typeOnly: false, dynamic: false },
      { specifier: './f.ts', line: 9, typeOnly: false, dynamic: true },
    ]);
  });
});

describe('checkImports', () => {
  it('refuses imports against the table, naming what the area may import, and allows the ones it lists', () => {
    expect(
      problems([
        file('server/a.ts', "import { connect } from '../sdk/index.ts';", "import { Room } from './room.ts';", "import { scenario } from '../scenarios/cubes-901.ts';"),
        file('sdk/b.ts', "import type { Room } from '../server/room.ts';", "import { encode } from '../shared/protocol/codec.ts';"),
        file('shared/sim/c.ts', "import { encode } from '../protocol/codec.ts';"),
        file('client/d.ts', "import { main } from '../cli/main.ts';", "import { connect } from '../sdk/index.ts';"),
        file('tests/e.ts', "import { main } from '../cli/main.ts';", "import { Room } from '../server/room.ts';"),
      ]),
    ).toEqual([
      'server/a.ts:2: server/ may not import sdk/ (sdk/index.ts); server/ may import: server, server/log, scenarios, shared/physics, shared/sim, shared/protocol, shared, shared/physics-data',
      'sdk/b.ts:2: sdk/ may not import server/ (server/room.ts); sdk/ may import: sdk, shared/protocol, shared/sim, shared, shared/physics-data',
      'shared/sim/c.ts:2: shared/sim/ may not import shared/protocol/ (shared/protocol/codec.ts); shared/sim/ may import: shared/sim, shared/physics, shared, shared/physics-data',
      'client/d.ts:2: client/ may not import cli/ (cli/main.ts); client/ may import: client, client/physics, sdk, shared/protocol, shared/sim, shared, shared/physics-data',
    ]);
  });

  it('lets examples import only the package\'s entry points and each other', () => {
    expect(
      problems([
        file('examples/g/game.ts', "import { defineScenario } from '../../api/index.ts';", "import { Room } from '../../server/room.ts';", "import { x } from './rules.ts';"),
        file('examples/g/rules.ts', "import { connect } from '../../api/client.ts';", "import { Simulation } from '../../shared/sim/simulation.ts';"),
      ]),
    ).toEqual([
      'examples/g/game.ts:3: examples/ may not import server/ (server/room.ts); examples/ may import: examples, api, api/client, api/physics',
      'examples/g/rules.ts:3: examples/ may not import shared/sim/ (shared/sim/simulation.ts); examples/ may import: examples, api, api/client, api/physics',
    ]);
  });

  it('lets other areas into the physics wrapper only through index.ts, and only shared/sim through internal.ts', () => {
    expect(
      problems([
        file('scenarios/a.ts', "import { PhysicsWorld } from '../shared/physics/index.ts';", "import { BodyTable } from '../shared/physics/body-table.ts';"),
        file('shared/sim/b.ts', "import { worldInternals } from '../physics/internal.ts';"),
        file('bench/c.ts', "import { worldInternals } from '../shared/physics/internal.ts';"),
        file('shared/physics/d.ts', "import { BodyTable } from './body-table.ts';"),
        file('tests/shared/physics/e.test.ts', "import { BodyTable } from '../../../shared/physics/body-table.ts';"),
      ]),
    ).toEqual([
      'scenarios/a.ts:3: import the physics wrapper through shared/physics/index.ts, not shared/physics/body-table.ts',
      'bench/c.ts:2: shared/physics/internal.ts is not public API: only shared/sim may import it',
    ]);
  });

  it('refuses browser code whose runtime imports reach the physics engine through another module, and follows no type-only import', () => {
    const sim = file('shared/sim/simulation.ts', "import { PhysicsWorld } from '../physics/index.ts';");
    const scene = file('shared/sim/scenario.ts', "import type { PhysicsWorldOptions } from '../physics/index.ts';");
    const helper = file('shared/sim/helper.ts', "import { Simulation } from './simulation.ts';");
    expect(
      problems([
        sim,
        scene,
        helper,
        file('client/a.ts', "import { helper } from '../shared/sim/helper.ts';"),
        file('shared/protocol/b.ts', "import type { Simulation } from '../sim/simulation.ts';", "import type { ScenarioDefinition } from '../sim/scenario.ts';"),
        file('sdk/c.ts', "import { type ScenarioDefinition } from '../shared/sim/scenario.ts';"),
      ]),
    ).toEqual(['client/a.ts:2: client/ must not pull in the physics engine: client/a.ts → shared/sim/helper.ts → shared/sim/simulation.ts → shared/physics/index.ts']);
  });

  it('lets browser code reach the physics chunk only by a dynamic import (tests as they like), and follows no such import looking for the engine', () => {
    const sim = file('shared/sim/simulation.ts', "import { PhysicsWorld } from '../physics/index.ts';");
    const chunk = file('client/physics/index.ts', "import { Simulation } from '../../shared/sim/simulation.ts';", "import { readLogBytes } from '../../server/log/log-bytes.ts';");
    expect(
      problems([
        sim,
        chunk,
        file('client/app/lazy.ts', "const physics = await import('../physics/index.ts');"),
        file('client/app/page.ts', "import { load } from './lazy.ts';", "import type { Simulation } from '../physics/index.ts';"),
        file('client/app/eager.ts', "import { Simulation } from '../physics/index.ts';"),
        file('sdk/d.ts', "const physics = await import('../client/physics/index.ts');"),
        file('client/e.ts', "import { readLogBytes } from '../server/log/log-bytes.ts';"),
        file('tests/client/f.test.ts', "import { ReplayPlayer } from '../../client/physics/index.ts';"),
      ]),
    ).toEqual([
      'client/app/eager.ts:2: load client/physics/index.ts with a dynamic import(): client/physics/ carries the physics engine, and a static import ships it with every page',
      'sdk/d.ts:2: sdk/ may not import client/physics/ (client/physics/index.ts); sdk/ may import: sdk, shared/protocol, shared/sim, shared, shared/physics-data',
      'client/e.ts:2: client/ may not import server/log/ (server/log/log-bytes.ts); client/ may import: client, client/physics, sdk, shared/protocol, shared/sim, shared, shared/physics-data',
    ]);
  });

  it('keeps Node and server packages out of browser areas and jolt-physics inside shared/physics', () => {
    expect(
      problems([
        file('sdk/a.ts', "import { readFile } from 'node:fs/promises';", "import { WebSocketServer } from 'ws';"),
        file('shared/protocol/b.ts', "import { pack } from 'msgpackr';"),
        file('server/c.ts', "import { WebSocketServer } from 'ws';", "import Jolt from 'jolt-physics';"),
        file('tests/d.ts', "import Jolt from 'jolt-physics/wasm';"),
        file('shared/physics/e.ts', "import Jolt from 'jolt-physics/wasm';"),
      ]),
    ).toEqual([
      'sdk/a.ts:2: sdk/ runs in the browser too: it may not import node:*',
      'sdk/a.ts:3: sdk/ runs in the browser too: it may not import ws',
      'server/c.ts:3: only shared/physics may import jolt-physics',
      'tests/d.ts:2: only shared/physics may import jolt-physics',
    ]);
  });

  it('finds no problem in this repository', () => {
    const root = fileURLToPath(new URL('../../', import.meta.url));
    const files: SourceFile[] = [];
    const walk = (dir: string): void => {
      for (const name of readdirSync(dir)) {
        const full = join(dir, name);
        if (statSync(full).isDirectory()) {
          if (!['node_modules', 'dist', 'results', 'fixtures'].includes(name)) walk(full);
        } else if (/\.(ts|js)$/.test(name)) {
          files.push({ path: relative(root, full).split(sep).join('/'), text: readFileSync(full, 'utf8') });
        }
      }
    };
    for (const top of ['shared', 'sdk', 'server', 'cli', 'client', 'scenarios', 'bench', 'tests', 'scripts', 'bin', 'api']) walk(join(root, top));
    expect(files.length).toBeGreaterThan(300);
    expect(problems(files)).toEqual([]);
  });
});
