// The import rules `npm run lint` enforces: which area of the repository may import which (the table below, the
// house plan of docs/architecture.md), the physics wrapper's two entry points, which packages browser-side code may
// use, and that code bound for the browser never pulls in the physics engine, directly or through another module,
// except through the one door it may: a dynamic import() of the physics chunk (client/physics/).
import { dirname, join, normalize } from 'node:path';

/** Areas by path prefix, most specific first: a file belongs to the first one its path starts with. */
const AREA_PREFIXES = [
  ['shared/physics-data/', 'shared/physics-data'],
  ['shared/physics/', 'shared/physics'],
  ['shared/sim/', 'shared/sim'],
  ['shared/protocol/', 'shared/protocol'],
  ['shared/', 'shared'],
  ['sdk/', 'sdk'],
  ['client/physics/', 'client/physics'],
  ['client/', 'client'],
  ['server/log/', 'server/log'],
  ['server/', 'server'],
  ['cli/', 'cli'],
  ['scenarios/', 'scenarios'],
  ['examples/', 'examples'],
  ['bench/', 'bench'],
  ['tests/', 'tests'],
  ['scripts/', 'scripts'],
  ['bin/', 'bin'],
  ['api/client.ts', 'api/client'],
  ['api/physics.ts', 'api/physics'],
  ['api/', 'api'],
] as const;

/** Every area. `shared` is the top-level modules of shared/ (clock.ts, byte-io.ts, tick-rate.ts). */
export type Area = (typeof AREA_PREFIXES)[number][1];

/** Plain data and pure helpers every layer may use. */
const SHARED_BASE: readonly Area[] = ['shared', 'shared/physics-data'];

/**
 * Which areas each area may import, besides itself. '*' means anything (tests, tools). Everything not listed is
 * refused: the arrows of the house run one way, from the page and the server down to shared/.
 */
export const MAY_IMPORT: Readonly<Record<Area, readonly Area[] | '*'>> = {
  // Leaves: pure data and helpers.
  shared: [],
  'shared/physics-data': [],
  // The Jolt wrapper: only Jolt itself and plain data.
  'shared/physics': SHARED_BASE,
  // The simulation drives the physics.
  'shared/sim': ['shared/physics', ...SHARED_BASE],
  // The wire speaks the simulation's data types, never the physics engine.
  'shared/protocol': ['shared/sim', ...SHARED_BASE],
  // Scenes are built on the simulation's and the physics wrapper's public API.
  scenarios: ['shared/sim', 'shared/physics', ...SHARED_BASE],
  // The client library (browsers and Node): the protocol and the simulation's data.
  sdk: ['shared/protocol', 'shared/sim', ...SHARED_BASE],
  // The page: the SDK and the data it hands over. It reaches client/physics/ (and so the engine) only by a dynamic
  // import(), which the build turns into a separate chunk that a page loads when it needs the simulation.
  client: ['client/physics', 'sdk', 'shared/protocol', 'shared/sim', ...SHARED_BASE],
  // The physics chunk of the page: the browser's own Simulation (replay viewer, predicted play).
  'client/physics': ['client', 'sdk', 'server/log', 'scenarios', 'shared/physics', 'shared/sim', 'shared/protocol', ...SHARED_BASE],
  // The input log's format: pure codecs (the replay page reads logs with them) beside the Node file reader and writer.
  'server/log': ['shared/sim', ...SHARED_BASE],
  // The server hosts simulations of the scenarios; it never imports the SDK, the page or the CLI.
  server: ['server/log', 'scenarios', 'shared/physics', 'shared/sim', 'shared/protocol', ...SHARED_BASE],
  // The command line composes everything but the page.
  cli: ['server', 'server/log', 'sdk', 'scenarios', 'shared/physics', 'shared/sim', 'shared/protocol', ...SHARED_BASE],
  bin: ['cli'],
  // The package's entry points: each re-exports a public surface. `taos-physics/client` is the SDK alone.
  api: ['api/physics', 'server', 'server/log', 'cli', 'sdk', 'scenarios', 'shared/physics', 'shared/sim', 'shared/protocol', ...SHARED_BASE],
  'api/client': ['sdk', 'shared/protocol', 'shared/sim', ...SHARED_BASE],
  // `taos-physics/physics` for browsers: the wrapper alone (Node gets api/physics-node.ts).
  'api/physics': ['shared/physics', ...SHARED_BASE],
  // Example games are written against the package's entry points only, as a project that installed it would be.
  examples: ['api', 'api/client', 'api/physics'],
  bench: '*',
  tests: '*',
  scripts: '*',
};

/** Packages (and node:* modules) areas that must run unchanged in the browser may import; other areas: any. */
export const MAY_USE_PACKAGES: Readonly<Partial<Record<Area, readonly string[]>>> = {
  shared: [],
  'shared/physics-data': [],
  'shared/physics': ['jolt-physics'],
  'shared/sim': [],
  'shared/protocol': ['msgpackr'],
  scenarios: [],
  sdk: [],
  client: [],
  'client/physics': [],
  'api/client': [],
  'api/physics': [],
};

/** Packages only these areas may import, wherever the importer is (tests and tools included). */
export const PACKAGE_ONLY_IN: Readonly<Record<string, readonly Area[]>> = {
  'jolt-physics': ['shared/physics'],
};

/** The files of shared/physics other areas may import, and who may import each ('*': any allowed importer). */
export const PHYSICS_ENTRY_POINTS: Readonly<Record<string, readonly Area[] | '*'>> = {
  'shared/physics/index.ts': '*',
  // Not public API: what checkpoints and the tick need beyond index.ts.
  'shared/physics/internal.ts': ['shared/sim'],
};

/** Areas allowed to import any file of shared/physics (unit tests of its internals). */
const PHYSICS_INTERNALS_OPEN_TO: readonly Area[] = ['tests'];

/** Areas whose code runs in the browser: no chain of runtime imports from them may reach the physics engine. */
export const ENGINE_FREE: readonly Area[] = ['shared', 'shared/physics-data', 'shared/protocol', 'sdk', 'client', 'api/client'];

/** One source file: its repository-relative path (forward slashes) and text. */
export interface SourceFile {
  path: string;
  text: string;
}

/** One broken rule, at a line of a file. */
export interface ImportProblem {
  file: string;
  line: number;
  message: string;
}

/** One import or re-export statement (static or dynamic with a literal specifier). */
export interface ImportStatement {
  specifier: string;
  line: number;
  /** `import type` / `export type`: erased, it loads nothing at run time. */
  typeOnly: boolean;
  /** `import('…')`: loaded when the code runs it; into client/physics/ it is a separate chunk. */
  dynamic: boolean;
}

/** The area a page may load only by a dynamic import(): it carries the physics engine. */
const LAZY_AREA: Area = 'client/physics';

/** The area a repository path belongs to, or null (files at the top, e.g. vitest.config.ts). */
export function areaOf(path: string): Area | null {
  for (const [prefix, area] of AREA_PREFIXES) if (path.startsWith(prefix)) return area;
  return null;
}

const STATIC_IMPORT = /^[ \t]*(?:import|export)\s+(type\s+)?(?:[^'";]*?\s+from\s*)?['"]([^'"\n]+)['"]/gm;
const DYNAMIC_IMPORT = /\bimport\(\s*['"]([^'"\n]+)['"]\s*\)/g;

function lineAt(text: string, index: number): number {
  let line = 1;
  for (let i = text.indexOf('\n'); i !== -1 && i < index; i = text.indexOf('\n', i + 1)) line++;
  return line;
}

/** Every import/export-from statement of a file, with the line where its specifier stands. */
export function parseImports(text: string): ImportStatement[] {
  const out: ImportStatement[] = [];
  for (const m of text.matchAll(STATIC_IMPORT)) {
    out.push({ specifier: m[2], line: lineAt(text, m.index + m[0].length - 1), typeOnly: m[1] !== undefined, dynamic: false });
  }
  for (const m of text.matchAll(DYNAMIC_IMPORT)) out.push({ specifier: m[1], line: lineAt(text, m.index), typeOnly: false, dynamic: true });
  return out;
}

/** The repository path a relative specifier names, or null for a package. */
function resolve(from: string, specifier: string): string | null {
  if (!specifier.startsWith('.')) return null;
  return normalize(join(dirname(from), specifier)).replace(/\\/g, '/');
}

/** The package a bare specifier names: `node:fs`, `ws`, `@scope/name`, `jolt-physics` for `jolt-physics/wasm`. */
function packageOf(specifier: string): string {
  if (specifier.startsWith('node:')) return 'node:*';
  const parts = specifier.split('/');
  return specifier.startsWith('@') ? parts.slice(0, 2).join('/') : parts[0];
}

function allowsArea(area: Area, target: Area): boolean {
  const rule = MAY_IMPORT[area];
  return area === target || rule === '*' || rule.includes(target);
}

/** Checks every rule over a set of files; imports of files outside the set are judged by their path alone. */
export function checkImports(files: readonly SourceFile[]): ImportProblem[] {
  const problems: ImportProblem[] = [];
  const imports = new Map(files.map((f) => [f.path, parseImports(f.text)]));
  const engineChain = engineReach(imports);
  for (const file of files) {
    const area = areaOf(file.path);
    if (area === null) continue;
    const report = (line: number, message: string): void => {
      problems.push({ file: file.path, line, message });
    };
    for (const imp of imports.get(file.path)!) {
      const target = resolve(file.path, imp.specifier);
      if (target === null) {
        const pkg = packageOf(imp.specifier);
        const only = PACKAGE_ONLY_IN[pkg];
        if (only && !only.includes(area)) report(imp.line, `only ${only.join(', ')} may import ${pkg}`);
        const allowed = MAY_USE_PACKAGES[area];
        if (!only && allowed && !allowed.includes(pkg)) {
          report(imp.line, `${area}/ runs in the browser too: it may not import ${pkg}${allowed.length ? ` (allowed: ${allowed.join(', ')})` : ''}`);
        }
        continue;
      }
      const targetArea = areaOf(target);
      if (targetArea === null) continue;
      if (!allowsArea(area, targetArea)) {
        const rule = MAY_IMPORT[area];
        const may = rule === '*' ? 'anything' : [area, ...rule].join(', ');
        report(imp.line, `${area}/ may not import ${targetArea}/ (${target}); ${area}/ may import: ${may}`);
        continue;
      }
      // Browser code crosses into the physics chunk only where it is split off: a dynamic import().
      const lazy = targetArea === LAZY_AREA && area !== LAZY_AREA && ENGINE_FREE.includes(area);
      if (lazy && !imp.dynamic && !imp.typeOnly) {
        report(imp.line, `load ${target} with a dynamic import(): ${LAZY_AREA}/ carries the physics engine, and a static import ships it with every page`);
        continue;
      }
      if (targetArea === 'shared/physics' && area !== 'shared/physics' && !PHYSICS_INTERNALS_OPEN_TO.includes(area)) {
        const entry = PHYSICS_ENTRY_POINTS[target];
        if (entry === undefined) report(imp.line, `import the physics wrapper through shared/physics/index.ts, not ${target}`);
        else if (entry !== '*' && !entry.includes(area)) report(imp.line, `${target} is not public API: only ${entry.join(', ')} may import it`);
      }
      if (ENGINE_FREE.includes(area) && !imp.typeOnly && !lazy) {
        const chain = targetArea === 'shared/physics' ? [target] : engineChain(target);
        if (chain) report(imp.line, `${area}/ must not pull in the physics engine: ${[file.path, ...chain].join(' → ')}`);
      }
    }
  }
  return problems;
}

/**
 * For a file, the chain of runtime imports by which it reaches the physics engine (shared/physics or the
 * jolt-physics package), or null. Type-only imports load nothing and are not followed.
 */
function engineReach(imports: ReadonlyMap<string, ImportStatement[]>): (path: string) => string[] | null {
  const cache = new Map<string, string[] | null>();
  return (start) => {
    if (cache.has(start)) return cache.get(start)!;
    const cameFrom = new Map<string, string | null>([[start, null]]);
    const queue = [start];
    let found: string[] | null = null;
    const chainTo = (last: string, end: string): string[] => {
      const chain = [end];
      for (let at: string | null = last; at !== null; at = cameFrom.get(at)!) chain.unshift(at);
      return chain;
    };
    search: while (queue.length > 0) {
      const path = queue.shift()!;
      for (const imp of imports.get(path) ?? []) {
        if (imp.typeOnly) continue;
        const target = resolve(path, imp.specifier);
        // A dynamic import of the physics chunk is where the engine is allowed in: the chunk loads on demand.
        if (imp.dynamic && target !== null && areaOf(target) === LAZY_AREA && areaOf(path) !== LAZY_AREA) continue;
        if (target === null) {
          if (packageOf(imp.specifier) === 'jolt-physics') {
            found = chainTo(path, 'jolt-physics');
            break search;
          }
          continue;
        }
        if (target.startsWith('shared/physics/')) {
          found = chainTo(path, target);
          break search;
        }
        if (!cameFrom.has(target)) {
          cameFrom.set(target, path);
          queue.push(target);
        }
      }
    }
    cache.set(start, found);
    return found;
  };
}
