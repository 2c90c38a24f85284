// `npm run gallery`: regenerates docs/img/ — every scenario in the follow view (what a player sees from its spawn)
// and the orbit view, shot in headless Chromium (WebGPU on SwiftShader) against a server started in this process —
// and docs/gallery.md, which shows them with the own avatar's share of the frame. Needs /usr/bin/chromium (or
// CHROMIUM_PATH).
import { mkdir, writeFile } from 'node:fs/promises';
import { join } from 'node:path';
import { scenarioNames } from '../scenarios/index.ts';
import { browserMissingReason, launchBrowser, startAppServer } from '../tests/helpers/browser.ts';
import { SHOT_PARAMS, shootScenarios } from '../tests/helpers/scenario-shots.ts';
import { buildClient } from './build-client.ts';

const root = new URL('../', import.meta.url).pathname;
const imgDir = join(root, 'docs/img');

async function main(): Promise<number> {
  const missing = browserMissingReason();
  if (missing) {
    process.stderr.write(`gallery: ${missing}\n`);
    return 1;
  }
  await mkdir(imgDir, { recursive: true });
  const built = await buildClient();
  const server = await startAppServer({ scenario: 'shape-rain', clientDir: built.outDir, params: { count: 1 } });
  const browser = await launchBrowser();
  const rows: string[] = [];
  try {
    await shootScenarios(browser, server.url, scenarioNames(), {
      image: 'jpeg',
      onShot: async (shot) => {
        await writeFile(join(imgDir, `${shot.scenario}-follow.jpg`), shot.follow);
        await writeFile(join(imgDir, `${shot.scenario}-orbit.jpg`), shot.orbit);
        const params = Object.entries(SHOT_PARAMS[shot.scenario] ?? {}).map(([k, v]) => `${k}=${v}`).join(' ');
        rows.push(`| \`${shot.scenario}\`${params ? ` (${params})` : ''} | ![${shot.scenario}, follow view](img/${shot.scenario}-follow.jpg) | ![${shot.scenario}, orbit view](img/${shot.scenario}-orbit.jpg) | ${(shot.ownAvatarCoverage * 100).toFixed(1)} % |`);
        process.stdout.write(`${shot.scenario}: own avatar ${(shot.ownAvatarCoverage * 100).toFixed(1)} % of the frame\n`);
      },
    });
  } finally {
    await browser.close();
    await server.close('gallery done');
  }
  const page = [
    '# Gallery',
    '',
    'Every scenario as a player sees it from its spawn point (follow camera) and as a spectator (orbit camera, V),',
    'rendered by the browser client in headless Chromium with WebGPU on SwiftShader at 640×360. Regenerate with',
    '`npm run gallery` (`scripts/gallery.ts`); `tests/client/follow-camera.browser.test.ts` checks the last column',
    '(the own capsule\'s share of the frame, an upper bound from its projected outline) stays under 15 %.',
    '',
    '| scenario | follow | orbit | own avatar |',
    '|---|---|---|---|',
    ...rows,
    '',
  ].join('\n');
  await writeFile(join(root, 'docs/gallery.md'), page);
  return 0;
}

process.exitCode = await main();
