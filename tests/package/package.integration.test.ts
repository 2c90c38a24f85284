// The package as a user gets it: `npm pack`, installed into an empty project outside the repository, with a
// scenario written there against the public exports. It serves the scenario, two clients (the installed
// `taos-physics/client`) play it, `run` gives the same hash twice, and the recording replays. `init` scaffolds a
// project that installs from the tarball, passes its own test and serves its page. examples/ball-goals, its imports
// pointed at the package, is served from the install and played with the game API (kick, score, resetBall).
import { execFile } from 'node:child_process';
import { readdir, readFile, rm, writeFile } from 'node:fs/promises';
import { join } from 'node:path';
import { promisify } from 'node:util';
import { afterAll, beforeAll, describe, expect, it } from 'vitest';
import { writeGameModule } from '../helpers/game-module.ts';
import { cliIn, NODE24, npmStartIn, packAndInstall, serveIn, stop, type PackedInstall } from './packed-package.ts';
import { dirname } from 'node:path';

const run = promisify(execFile);
let pkg: PackedInstall;

// Two players on the installed client library: each joins, counts snapshots, steers a little, then leaves.
const CLIENT_SCRIPT = `import { connect } from 'taos-physics/client';
const url = process.argv[2];
const play = (name) => new Promise((resolve, reject) => {
  const c = connect(url, { name, reconnect: false });
  let snapshots = 0;
  const timer = setTimeout(() => reject(new Error(name + ': only ' + snapshots + ' snapshots')), 20000);
  c.on('snapshot', () => {
    snapshots++;
    c.setInput({ moveX: 0, moveZ: -127, yaw: 0, pitch: 0, buttons: 0 });
    if (snapshots === 20) { clearTimeout(timer); c.close(); resolve({ name, scenario: c.welcome.scenario.name, playerId: c.welcome.playerId, snapshots }); }
  });
});
console.log(JSON.stringify(await Promise.all([play('ann'), play('bob')])));
`;

// Ball Goals on the installed client library: red walks at the ball holding the game's kick button until both players
// see the score change, then asks for the ball back with the resetBall message.
const BALL_GOALS_SCRIPT = `import { connect } from 'taos-physics/client';
const url = process.argv[2];
const red = connect(url, { name: 'red', reconnect: false });
const blue = connect(url, { name: 'blue', reconnect: false });
await Promise.all([red.whenConnected(), blue.whenConnected()]);
red.setInput({ moveX: 0, moveZ: 127, yaw: 0, pitch: 0, buttons: 0, kick: 1 });
const deadline = Date.now() + 20000;
while (!(red.gameState().scoreBlue === 1 && blue.gameState().scoreBlue === 1)) {
  if (Date.now() > deadline) throw new Error('no goal: ' + JSON.stringify(blue.gameState()));
  await new Promise((r) => setTimeout(r, 20));
}
red.setInput({ moveX: 0, moveZ: 0, yaw: 0, pitch: 0, buttons: 0 });
red.sendMessage('resetBall');
await new Promise((r) => setTimeout(r, 200));
console.log(JSON.stringify({ input: red.welcome.scenario.game.input, state: blue.gameState() }));
red.close();
blue.close();
`;

/** examples/ball-goals/game.ts as a project of its own would write it: importing the package by name. */
async function writeBallGoals(dir: string): Promise<void> {
  const source = await readFile(new URL('../../examples/ball-goals/game.ts', import.meta.url), 'utf8');
  await writeFile(join(dir, 'ball-goals.ts'), source.replace("from '../../api/index.ts'", "from 'taos-physics'"));
}

beforeAll(async () => {
  pkg = await packAndInstall();
  await writeBallGoals(pkg.app);
  await writeFile(join(pkg.app, 'ball-goals-play.mjs'), BALL_GOALS_SCRIPT);
  await writeGameModule(pkg.app, { importFrom: 'taos-physics' });
  await writeFile(join(pkg.app, 'players.mjs'), CLIENT_SCRIPT);
  console.log(`package: tarball ${pkg.tarballBytes} bytes, install ${(pkg.installMs / 1000).toFixed(1)} s`);
}, 300_000);
afterAll(async () => {
  if (pkg) await rm(pkg.root, { recursive: true, force: true });
});

describe('the packed package', () => {
  it('runs a scenario written in the project twice to the same hash', async () => {
    const a = await cliIn(pkg.app, ['run', '--scenario', './game.ts', '--ticks', '120', '--bots', '2', '--json']);
    const b = await cliIn(pkg.app, ['run', '--scenario', './game.ts', '--ticks', '120', '--bots', '2', '--json']);
    expect(a.code, a.stderr).toBe(0);
    expect(JSON.parse(a.stdout)).toMatchObject({ scenario: 'crate-drop', ticks: 120 });
    expect(JSON.parse(b.stdout).hash).toBe(JSON.parse(a.stdout).hash);
  }, 60_000);

  it('serves the scenario and its page, two clients play it, and the recording replays and verifies', async () => {
    const server = await serveIn(pkg.app, ['--scenario', './game.ts', '--record', 'rec']);
    let code: number | null;
    try {
      const page = await fetch(server.url);
      expect(page.status).toBe(200);
      expect(await page.text()).toMatch(/<html/i);
      const players = await run(NODE24, ['players.mjs', server.wsUrl], { cwd: pkg.app });
      const result = JSON.parse(players.stdout) as Array<{ scenario: string; snapshots: number }>;
      expect(result.map((p) => [p.scenario, p.snapshots])).toEqual([
        ['crate-drop', 20],
        ['crate-drop', 20],
      ]);
    } finally {
      code = await stop(server.child);
    }
    expect(code, server.output()).toBe(0);
    const [log] = await readdir(join(pkg.app, 'rec'));
    const replay = await cliIn(pkg.app, ['replay', join('rec', log), '--scenario', './game.ts', '--json']);
    expect(replay.code, replay.stderr).toBe(0);
    expect(JSON.parse(replay.stdout)).toMatchObject({ status: 'ok', scenario: 'crate-drop' });
    expect(JSON.parse(replay.stdout).ticks).toBeGreaterThan(0);
    const verify = await cliIn(pkg.app, ['verify', join('rec', log), '--scenario', './game.ts', '--runs', '2', '--json']);
    expect(verify.code, verify.stderr).toBe(0);
    expect(JSON.parse(verify.stdout)).toMatchObject({ agree: true, matchesLog: true });
  }, 90_000);

  it('plays examples/ball-goals from the install: a kick scores for both players, and the recording replays', async () => {
    const server = await serveIn(pkg.app, ['--scenario', './ball-goals.ts', '--record', 'rec-goals']);
    let code: number | null;
    try {
      const played = await run(NODE24, ['ball-goals-play.mjs', server.wsUrl], { cwd: pkg.app });
      expect(JSON.parse(played.stdout)).toEqual({ input: [{ name: 'kick', min: 0, max: 1 }], state: { scoreRed: 0, scoreBlue: 1, lastGoal: 'blue' } });
    } finally {
      code = await stop(server.child);
    }
    expect(code, server.output()).toBe(0);
    const [log] = await readdir(join(pkg.app, 'rec-goals'));
    const replay = await cliIn(pkg.app, ['replay', join('rec-goals', log), '--scenario', './ball-goals.ts', '--json']);
    expect(replay.code, replay.stderr).toBe(0);
    expect(JSON.parse(replay.stdout)).toMatchObject({ status: 'ok', scenario: 'ball-goals' });
  }, 90_000);

  it('exports the server, client, physics and sim entries with types, and nothing else', async () => {
    const script = `
      const main = await import('taos-physics');
      const client = await import('taos-physics/client');
      const physics = await import('taos-physics/physics');
      const sim = await import('taos-physics/sim');
      const { scenario } = await import('./game.ts');
      const s = await sim.Simulation.create({ scenario, seed: 3 });
      for (let t = 0; t < 30; t++) s.step(sim.emptyTickInput(t));
      let internal = 'exported';
      try { await import('taos-physics/dist/server/room.js'); } catch (e) { internal = e.code; }
      console.log(JSON.stringify({ main: typeof main.createServer + typeof main.defineScenario, client: typeof client.connect, physics: typeof physics.PhysicsWorld, sim: typeof sim.replayLog, tick: s.tick, internal }));
      s.destroy();`;
    const out = await run(NODE24, ['--input-type=module', '-e', script], { cwd: pkg.app });
    expect(JSON.parse(out.stdout)).toEqual({ main: 'functionfunction', client: 'function', physics: 'function', sim: 'function', tick: 30, internal: 'ERR_PACKAGE_PATH_NOT_EXPORTED' });
    const types = await readdir(join(pkg.app, 'node_modules', 'taos-physics', 'dist', 'api'));
    expect(types).toEqual(expect.arrayContaining(['index.d.ts', 'client.d.ts', 'physics.d.ts', 'physics-node.d.ts', 'sim.d.ts']));
  }, 60_000);

  it("bundles the client and physics entries for browsers without the package's Node code", async () => {
    // Jolt's own glue imports node:module on its Node path only: bundlers leave it external (docs/reference.md).
    const script = `
      import { build } from 'esbuild';
      const r = await build({ stdin: { contents: "export { connect } from 'taos-physics/client'; export { PhysicsWorld } from 'taos-physics/physics';", resolveDir: process.cwd() }, bundle: true, platform: 'browser', format: 'esm', external: ['node:module'], write: false, metafile: true, logLevel: 'silent' });
      console.log(JSON.stringify(Object.keys(r.metafile.inputs).filter((p) => p.includes('taos-physics/dist/'))));`;
    const out = await run(NODE24, ['--input-type=module', '-e', script], { cwd: pkg.app });
    const inputs = JSON.parse(out.stdout) as string[];
    expect(inputs).toEqual(expect.arrayContaining([expect.stringContaining('dist/api/client.js'), expect.stringContaining('dist/api/physics.js')]));
    expect(inputs.filter((p) => p.includes('/server/') || p.includes('physics-node'))).toEqual([]);
  }, 60_000);

  it('init scaffolds a project that installs from the tarball (npm install), passes its own test and serves its page (npm start)', async () => {
    const started = performance.now();
    const init = await cliIn(pkg.root, ['init', 'ball-game', '--dependency', pkg.tarball], pkg.app);
    expect(init.code, init.stderr).toBe(0);
    const project = join(pkg.root, 'ball-game');
    await run('npm', ['install', '--prefer-offline', '--no-audit', '--no-fund'], { cwd: project });
    const env = { ...process.env, PATH: `${dirname(NODE24)}:${process.env.PATH}` };
    const test = await run('npm', ['test'], { cwd: project, env });
    expect(test.stdout).toMatch(/pass 2\n\S* ?fail 0/);
    const server = await npmStartIn(project);
    try {
      const page = await fetch(server.url);
      expect(await page.text()).toContain('<title>ball-game</title>');
      console.log(`init → served page: ${((performance.now() - started) / 1000).toFixed(1)} s (npm test included)`);
      expect((await fetch(new URL('/kit.js', server.url))).status).toBe(200);
      const scenarios = (await (await fetch(new URL('/api/scenarios', server.url))).json()) as { scenarios: Array<{ name: string }> };
      expect(scenarios.scenarios.map((s) => s.name)).toEqual(['ball-game']);
    } finally {
      await stop(server.child, true);
    }
  }, 120_000);
});
