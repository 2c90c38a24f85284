// Project lint: the house rules a generic linter can't know (pure shared/, no engine trig, headers, sizes, no enum,
// and the import rules of scripts/import-rules.ts: which folder may import which).
// Usage: node scripts/lint.js  — prints each violation as file:line: message and exits 1 if any.
import { readFileSync, readdirSync, statSync } from 'node:fs';
import { join, relative, sep } from 'node:path';
import { checkImports } from './import-rules.ts';

const root = new URL('..', import.meta.url).pathname;
const roots = ['shared', 'sdk', 'server', 'cli', 'client', 'scenarios', 'examples', 'tests', 'bench', 'scripts', 'bin', 'api'];
const skipDirs = new Set(['node_modules', 'dist', 'results', 'fixtures']);

function walk(dir, out) {
  let entries;
  try {
    entries = readdirSync(dir);
  } catch {
    return out;
  }
  for (const name of entries) {
    const full = join(dir, name);
    if (statSync(full).isDirectory()) {
      if (!skipDirs.has(name)) walk(full, out);
    } else if (/\.(ts|js|mjs)$/.test(name)) {
      out.push(full);
    }
  }
  return out;
}

const problems = [];
const report = (file, line, msg) => problems.push(`${relative(root, file)}:${line}: ${msg}`);
const files = roots.flatMap((r) => walk(join(root, r), []));

for (const file of files) {
  const rel = relative(root, file);
  const text = readFileSync(file, 'utf8');
  const lines = text.split('\n');
  const first = lines[0].startsWith('#!') ? lines[1] : lines[0];
  if (!/^\s*(\/\/|\/\*)/.test(first ?? '')) report(file, 1, 'a file opens with a short comment on what it owns');
  if (lines.length > 600) report(file, lines.length, `file has ${lines.length} lines; split it by concern (limit 600)`);
  const isShared = rel.startsWith('shared/') || rel.startsWith('scenarios/');
  lines.forEach((raw, i) => {
    const line = raw.replace(/\/\/.*$/, '');
    const n = i + 1;
    if (/^\s*(export\s+)?(const\s+)?enum\s/.test(line)) report(file, n, 'no enum: use an `as const` object');
    if (/^export default/.test(line) && !rel.endsWith('vitest.config.ts')) report(file, n, 'named exports only');
    if (isShared) {
      if (/from ['"]node:|require\(|Math\.random\(|Date\.now\(|performance\.now\(|new Date\(|process\.|setTimeout\(|setInterval\(|\bwindow\.|\bdocument\./.test(line)) {
        report(file, n, 'shared/ and scenarios/ are pure and deterministic: no node:*, clocks, timers, Math.random, DOM');
      }
      if (/Math\.(sin|cos|tan|asin|acos|atan|atan2|exp|expm1|log|log1p|log2|log10|pow|hypot|cbrt|sinh|cosh|tanh)\(/.test(line)) {
        report(file, n, 'engine-dependent Math function in simulation code: use shared/sim/det-math.ts');
      }
      if (/\*\*/.test(line) && !/^\s*\*/.test(raw) && !/\/\*\*/.test(line)) report(file, n, '`**` may call pow: use multiplication');
    }
  });
}

const sources = files.map((file) => ({ path: relative(root, file).split(sep).join('/'), text: readFileSync(file, 'utf8') }));
for (const p of checkImports(sources)) problems.push(`${p.file}:${p.line}: ${p.message}`);

if (problems.length > 0) {
  console.error(problems.join('\n'));
  console.error(`\nlint: ${problems.length} problem(s) in ${files.length} files`);
  process.exit(1);
}
console.log(`lint: ${files.length} files clean`);
