// Re-runs every scenario's golden script and compares with scenarios/<name>.golden.json; the ONLY tool that rewrites
// those files, and only with --write. Usage: node_modules/.bin/node scripts/update-goldens.ts [--write] [NAME ...]
import { existsSync, readFileSync, writeFileSync } from 'node:fs';
import { fileURLToPath } from 'node:url';
import { installedJoltVersion } from '../server/log/jolt-version.ts';
import '../server/physics-node.ts';
import { getScenario, listScenarios } from '../scenarios/index.ts';
import { formatGoldenFile, parseGoldenFile, runGolden, type GoldenFile } from '../shared/sim/golden.ts';

/** Where a scenario's golden file lives. */
function goldenPath(name: string): string {
  return fileURLToPath(new URL(`../scenarios/${name}.golden.json`, import.meta.url));
}

function readGolden(name: string): GoldenFile | null {
  const path = goldenPath(name);
  if (!existsSync(path)) return null;
  return parseGoldenFile(JSON.parse(readFileSync(path, 'utf8')), path);
}

async function main(argv: string[]): Promise<number> {
  const write = argv.includes('--write');
  const unknownFlag = argv.find((a) => a.startsWith('-') && a !== '--write');
  if (unknownFlag) {
    console.error(`update-goldens: unknown option ${unknownFlag}\nusage: update-goldens.ts [--write] [SCENARIO ...]`);
    return 2;
  }
  const names = argv.filter((a) => !a.startsWith('-'));
  let defs;
  try {
    defs = names.length > 0 ? names.map((n) => getScenario(n)) : [...listScenarios()];
  } catch (err) {
    console.error(`update-goldens: ${(err as Error).message}`);
    return 2;
  }
  const jolt = installedJoltVersion();
  let differing = 0;
  for (const def of defs) {
    const started = performance.now();
    const result = await runGolden(def);
    const msPerTick = (performance.now() - started) / result.ticks;
    const stored = readGolden(def.name);
    const same = stored !== null && stored.hash === result.hash && stored.ticks === result.ticks && stored.bots === result.bots && stored.seed === result.seed && stored.joltVersion === jolt;
    const status = stored === null ? 'new' : same ? 'same' : `changed (was ${stored.hash}, jolt ${stored.joltVersion})`;
    console.log(`${def.name.padEnd(18)} ${result.hash}  ${String(result.ticks).padStart(5)} ticks  ${result.bots} bots  ${msPerTick.toFixed(2).padStart(7)} ms/tick  ${status}`);
    if (same) continue;
    differing++;
    if (write) {
      writeFileSync(goldenPath(def.name), formatGoldenFile(result, jolt));
      console.log(`  wrote ${goldenPath(def.name)}`);
    }
  }
  if (differing > 0 && !write) {
    console.error(`\n${differing} golden(s) differ or are missing; rerun with --write to record them (only if the change is intended)`);
    return 1;
  }
  return 0;
}

process.exitCode = await main(process.argv.slice(2));
