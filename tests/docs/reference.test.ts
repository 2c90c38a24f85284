// docs/reference.md names every value each package entry exports, in that entry's section: a new export without
// a line in the reference fails here.
import { readFile } from 'node:fs/promises';
import { describe, expect, it } from 'vitest';

const ENTRIES = [
  { heading: '## `taos-physics`\n', module: '../../api/index.ts' },
  { heading: '## `taos-physics/client`\n', module: '../../api/client.ts' },
  { heading: '## `taos-physics/physics`\n', module: '../../api/physics-node.ts' },
  { heading: '## `taos-physics/sim`\n', module: '../../api/sim.ts' },
] as const;

/** The reference's section under `heading`, up to the next `## `. */
function section(text: string, heading: string): string {
  const start = text.indexOf(heading);
  if (start < 0) throw new Error(`docs/reference.md has no section ${heading.trim()}`);
  const end = text.indexOf('\n## ', start + heading.length);
  return text.slice(start, end < 0 ? undefined : end);
}

describe('docs/reference.md', () => {
  for (const entry of ENTRIES) {
    it(`lists every value ${entry.heading.trim().slice(3)} exports`, async () => {
      const text = await readFile(new URL('../../docs/reference.md', import.meta.url), 'utf8');
      // The sim entry re-exports the scenario kit, listed once in the main entry's section.
      const where = entry.module.endsWith('sim.ts') ? section(text, ENTRIES[3].heading) + section(text, ENTRIES[0].heading) : section(text, entry.heading);
      const names = Object.keys((await import(entry.module)) as Record<string, unknown>);
      expect(names.length).toBeGreaterThan(0);
      expect(names.filter((n) => !new RegExp(`\`${n}[\`(]`).test(where))).toEqual([]);
    });
  }
});
