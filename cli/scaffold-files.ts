// The files `taos-physics init NAME` writes: a game project on the installed package. A scenario (players push balls
// into a goal, a replicated goal event), a page on the client library and the stock renderer, a test, a README.
// Pure: returns the files' text; init-command.ts writes them.

/** What the scaffold needs to know. */
export interface ScaffoldOptions {
  /** npm package name of the new project (also the scenario's name). */
  name: string;
  /** Version range of taos-physics the project depends on. */
  dependency: string;
}

const SCENARIO = `// The game's rules: a walled pitch, balls, and a goal. Players walk into balls (or shoot them) to push them into
// the goal; each goal is reported to every player as a 'goal' event and the ball comes back at the centre.
// Everything here runs on the server's fixed 60 Hz tick and replays bit for bit: randomness only from ctx.rng.
import { CollisionLayer, defineScenario, type ScenarioContext } from 'taos-physics';

const PITCH_HALF_METRES = 12;
const GOAL_Z = -PITCH_HALF_METRES + 1.5;

function spawnBall(ctx: ScenarioContext): number {
  const x = ctx.rng.range(-4, 4);
  const z = ctx.rng.range(-2, 4);
  return ctx.spawn({ kind: 'sphere', radius: 0.5 }, { x, y: 3, z }, null, { color: [0.95, 0.55, 0.1], friction: 0.4, restitution: 0.5 }).id;
}

export const scenario = defineScenario({
  name: '__NAME__',
  description: 'Push the balls into the goal',
  params: {
    balls: { default: 5, min: 1, max: 40, integer: true, description: 'balls on the pitch' },
  },
  bounds: { min: { x: -20, y: -5, z: -20 }, max: { x: 20, y: 30, z: 20 } },
  players: { walkSpeedMetresPerSecond: 5 },
  build(ctx) {
    const half = PITCH_HALF_METRES;
    ctx.spawn({ kind: 'box', halfExtents: { x: half, y: 0.5, z: half } }, { x: 0, y: -0.5, z: 0 }, null, { motion: 'static', color: [0.3, 0.55, 0.3] });
    for (const [hx, hz, x, z] of [[half, 0.25, 0, -half], [half, 0.25, 0, half], [0.25, half, -half, 0], [0.25, half, half, 0]]) {
      ctx.spawn({ kind: 'box', halfExtents: { x: hx, y: 1, z: hz } }, { x, y: 1, z }, null, { motion: 'static', color: [0.6, 0.6, 0.62] });
    }
    // The goal: a sensor volume that sees balls (dynamic bodies are on the Prop layer).
    const goal = ctx.spawn({ kind: 'box', halfExtents: { x: 3, y: 1.5, z: 1 } }, { x: 0, y: 1.5, z: GOAL_Z }, null, {
      motion: 'static',
      isSensor: true,
      mask: CollisionLayer.Prop,
      color: [0.9, 0.9, 0.2],
    }).id;
    let balls: number[] = [];
    let goals = 0;
    return {
      spawnPoint: (n) => ({ x: (n % 4) * 1.5 - 2.25, y: 0.05, z: half - 3 }),
      onTick(c) {
        while (balls.length < c.params.balls) balls.push(spawnBall(c));
      },
      onEvents(c, events) {
        for (const e of events) {
          if (e.type !== 'sensorEnter' || e.sensorId !== goal || !balls.includes(e.bodyId)) continue;
          goals++;
          c.emit('goal', goals);
          c.remove(e.bodyId);
          balls = balls.filter((id) => id !== e.bodyId);
        }
      },
      saveState: () => [goals, ...balls],
      restoreState: (s) => {
        goals = s[0];
        balls = s.slice(1);
      },
    };
  },
});
`;

const TEST = `// The game's own tests (node --test): the scenario is deterministic, and a recorded session replays.
import { mkdtemp, rm } from 'node:fs/promises';
import { tmpdir } from 'node:os';
import { join } from 'node:path';
import { test } from 'node:test';
import assert from 'node:assert/strict';
import { BotScript, replayLog, SessionLog, Simulation } from 'taos-physics/sim';
import { scenario } from './game.ts';

async function finalHash(seed: number, ticks: number): Promise<string> {
  const sim = await Simulation.create({ scenario, seed });
  const bots = new BotScript({ seed, bots: 2 });
  for (let t = 0; t < ticks; t++) sim.step(bots.next());
  const hash = sim.stateHash();
  sim.destroy();
  return hash;
}

test('the same seed and inputs give the same state', async () => {
  assert.equal(await finalHash(7, 240), await finalHash(7, 240));
});

test('a recorded session replays with every hash matching', async () => {
  const dir = await mkdtemp(join(tmpdir(), '__NAME__-'));
  try {
    const file = join(dir, 'session.tlog');
    const sim = await Simulation.create({ scenario, seed: 3 });
    const log = await SessionLog.create(file, sim);
    const bots = new BotScript({ seed: 3, bots: 2 });
    for (let t = 0; t < 180; t++) log.step(bots.next());
    await log.close();
    sim.destroy();
    const report = await replayLog(file, { scenario });
    assert.equal(report.status, 'ok');
    assert.equal(report.ticks, 180);
  } finally {
    await rm(dir, { recursive: true, force: true });
  }
});
`;

const PAGE = `<!doctype html>
<!-- The game's page: the stock WebGPU view (play() from /kit.js, which the server provides) and a goal counter. -->
<html lang="en">
  <head>
    <meta charset="utf-8" />
    <meta name="viewport" content="width=device-width, initial-scale=1" />
    <title>__NAME__</title>
    <link rel="icon" href="data:," />
    <style>
      html, body { margin: 0; height: 100%; background: #223; color: #eee; font: 16px system-ui, sans-serif; }
      canvas { display: block; width: 100%; height: 100%; }
      #score { position: fixed; top: 12px; left: 12px; padding: 6px 10px; background: #0008; border-radius: 6px; }
    </style>
  </head>
  <body>
    <canvas id="view" tabindex="0"></canvas>
    <div id="score">connecting…</div>
    <script type="module">
      import { play } from '/kit.js';
      const score = document.getElementById('score');
      try {
        const game = await play(document.getElementById('view'));
        game.client.on('welcome', () => (score.textContent = 'goals: 0 · WASD moves, mouse looks, click fires'));
        game.client.on('events', (events) => {
          for (const e of events) if (e.type === 'scenario' && e.name === 'goal') score.textContent = 'goals: ' + e.value;
        });
        game.client.on('closed', (c) => (score.textContent = 'disconnected: ' + c.reason));
      } catch (err) {
        score.textContent = err.message;
      }
    </script>
  </body>
</html>
`;

const README = `# __NAME__

A multiplayer physics game on the taos-physics package: the server runs the world, browsers draw it.

\`\`\`sh
npm install
npm start        # serves the game at http://127.0.0.1:8080/ (open it in two browser tabs)
\`\`\`

Node 24 and a browser with WebGPU (Chrome/Edge) are all it needs.

- \`game.ts\`: the rules (a scenario): the scene, what happens each tick, where players appear.
- \`page/index.html\`: the page: the stock view from \`/kit.js\` and a goal counter.
- \`game.test.ts\`: \`npm test\` checks that the game is deterministic and that a recorded session replays.

Recording and replaying a session:

\`\`\`sh
npx taos-physics record --scenario ./game.ts --bots 4 --ticks 1800 --out session.tlog
npx taos-physics replay session.tlog --scenario ./game.ts
\`\`\`
`;

/** The project's files by relative path. */
export function scaffoldFiles(opts: ScaffoldOptions): Record<string, string> {
  const fill = (text: string): string => text.replaceAll('__NAME__', opts.name);
  const pkg = {
    name: opts.name,
    version: '0.1.0',
    private: true,
    type: 'module',
    scripts: {
      start: 'taos-physics serve --scenario ./game.ts --page ./page',
      test: 'node --test game.test.ts',
    },
    engines: { node: '>=24' },
    dependencies: { 'taos-physics': opts.dependency },
  };
  // For editors: Node runs the .ts files directly (type stripping); nothing compiles them.
  const tsconfig = {
    compilerOptions: { target: 'ES2023', module: 'nodenext', moduleResolution: 'nodenext', allowImportingTsExtensions: true, noEmit: true, strict: true, skipLibCheck: true, lib: ['ES2023', 'DOM'] },
    include: ['*.ts'],
  };
  return {
    'package.json': `${JSON.stringify(pkg, null, 2)}\n`,
    'tsconfig.json': `${JSON.stringify(tsconfig, null, 2)}\n`,
    'game.ts': fill(SCENARIO),
    'game.test.ts': fill(TEST),
    'page/index.html': fill(PAGE),
    'README.md': fill(README),
    '.gitignore': 'node_modules/\n*.tlog\n',
  };
}
