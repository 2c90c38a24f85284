// Command-line flags of `npm run bench`: --quick, --json, --peers, --only NAME, --out DIR, --help. Unknown flags and
// unknown figure names are refused with a clear message (a typo must not silently run the 15-minute suite).

/** Parsed bench options. */
export interface BenchArgs {
  quick: boolean;
  json: boolean;
  peers: boolean;
  /** Figure names to run (empty: all). */
  only: string[];
  /** Where results go; null: bench/results. */
  outDir: string | null;
  help: boolean;
}

/** Usage text. */
export function benchUsage(figureNames: readonly string[]): string {
  return [
    'usage: npm run bench -- [--quick] [--json] [--peers] [--only NAME]… [--out DIR]',
    '',
    '  --quick      coarse run, about a minute (fewer samples, shorter scenes, coarse client search)',
    '  --json       print the result object on stdout (the table goes to stderr)',
    '  --peers      also run the engine peer (the same pile in Rapier)',
    '  --only NAME  run only this figure (repeatable); results are not written unless --out is given',
    '  --out DIR    write latest.json, latest.md and the charts into DIR (default bench/results)',
    '',
    `figures: ${figureNames.join(', ')}`,
    '',
  ].join('\n');
}

/** Parses argv (after the script name). Throws an Error naming the problem. */
export function parseBenchArgs(argv: readonly string[], figureNames: readonly string[]): BenchArgs {
  const out: BenchArgs = { quick: false, json: false, peers: false, only: [], outDir: null, help: false };
  for (let i = 0; i < argv.length; i++) {
    const a = argv[i];
    const [flag, inline] = a.startsWith('--') && a.includes('=') ? [a.slice(0, a.indexOf('=')), a.slice(a.indexOf('=') + 1)] : [a, undefined];
    const value = (): string => {
      if (inline !== undefined) return inline;
      const v = argv[i + 1];
      if (v === undefined || v.startsWith('--')) throw new Error(`${flag} needs a value`);
      i++;
      return v;
    };
    switch (flag) {
      case '--quick':
        out.quick = true;
        break;
      case '--json':
        out.json = true;
        break;
      case '--peers':
        out.peers = true;
        break;
      case '--help':
      case '-h':
        out.help = true;
        break;
      case '--only': {
        const name = value();
        if (!figureNames.includes(name)) throw new Error(`unknown figure "${name}" (figures: ${figureNames.join(', ')})`);
        if (!out.only.includes(name)) out.only.push(name);
        break;
      }
      case '--out': {
        const dir = value();
        if (dir === '') throw new Error('--out needs a directory');
        out.outDir = dir;
        break;
      }
      default:
        throw new Error(`unknown argument "${a}"`);
    }
  }
  return out;
}
