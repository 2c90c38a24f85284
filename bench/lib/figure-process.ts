// Entry point of one figure's own process (the runner spawns it, so figures never share a Jolt heap, a JIT or a GC):
// `node bench/lib/figure-process.ts NAME RESULT_FILE [--quick]` runs the figure and writes its output as JSON.
import { writeFile } from 'node:fs/promises';
import { FIGURES } from '../figures/index.ts';
import type { FigureImpl } from './figure.ts';

const [name, resultFile, ...rest] = process.argv.slice(2);
const spec = FIGURES.find((f) => f.name === name);
if (!spec || !resultFile) {
  process.stderr.write(`usage: node bench/lib/figure-process.ts NAME RESULT_FILE [--quick] (figures: ${FIGURES.map((f) => f.name).join(', ')})\n`);
  process.exit(2);
}
const quick = rest.includes('--quick');
const log = (message: string): void => void process.stderr.write(`  [${spec.name}] ${message}\n`);

try {
  const mod = (await import(new URL(`../${spec.module}`, import.meta.url).href)) as { figure?: FigureImpl };
  if (!mod.figure || typeof mod.figure.run !== 'function') throw new Error(`${spec.module} does not export a figure`);
  const output = await mod.figure.run({ quick, log });
  await writeFile(resultFile, JSON.stringify({ ok: true, output }));
  // Figures close what they open, but a stray handle (a socket, a timer) must not hold the runner up.
  process.exit(0);
} catch (error) {
  const message = error instanceof Error ? (error.stack ?? error.message) : String(error);
  log(`failed: ${message}`);
  await writeFile(resultFile, JSON.stringify({ ok: false, error: error instanceof Error ? error.message : String(error) }));
  process.exit(1);
}
