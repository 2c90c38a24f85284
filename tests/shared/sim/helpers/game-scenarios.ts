// A small scenario that uses the game API: a ball on a floor that each player's game input pushes (an axis and a
// button). Tests of game input, replicated state and game messages build on it.
import type { ScenarioDefinition } from '../../../../shared/sim/scenario.ts';

/** The ball's body id in pushBallScenario (the floor is 1). */
export const PUSH_BALL_ID = 2;

/**
 * A floor and a ball; every tick each player's `push` (−100…100) sets the ball's x speed, `lift` (a button) its y
 * speed. Game state: `phase` is 'pushing' on ticks with a push and 'idle' otherwise; `pushTicks` counts those ticks.
 */
export const pushBallScenario: ScenarioDefinition = {
  name: 'test-push-ball',
  description: 'Game input pushes a ball.',
  params: {},
  bounds: { min: { x: -30, y: -5, z: -30 }, max: { x: 30, y: 30, z: 30 } },
  golden: { ticks: 60, bots: 1 },
  input: { push: { kind: 'axis', min: -100, max: 100 }, lift: { kind: 'button' } },
  state: { phase: { kind: 'string', maxLength: 8, initial: 'idle' }, pushTicks: { kind: 'number' } },
  build(ctx) {
    ctx.spawn({ kind: 'box', halfExtents: { x: 25, y: 0.5, z: 25 } }, { x: 0, y: -0.5, z: 0 }, null, { motion: 'static', name: 'floor' });
    const ball = ctx.spawn({ kind: 'sphere', radius: 0.5 }, { x: 0, y: 0.5, z: 5 }, null, { motion: 'dynamic', name: 'ball' });
    const ballId = ball.id;
    return {
      spawnPoint: (n) => ({ x: -4 + 2 * n, y: 0.05, z: -5 }),
      onTick(c) {
        let pushing = false;
        for (const cmd of c.inputs()) {
          const g = c.gameInput(cmd.playerId);
          if (g.push !== 0 || g.lift !== 0) c.world.setLinearVelocity(ballId, { x: g.push / 20, y: g.lift * 3, z: 0 });
          pushing ||= g.push !== 0;
        }
        c.setState('phase', pushing ? 'pushing' : 'idle');
        if (pushing) c.setState('pushTicks', (c.getState('pushTicks') as number) + 1);
      },
    };
  },
};

/** pushBallScenario plus game messages: `pickTeam {team: 0…1}` sets `lastPick` to playerId·10 + team; `ready` adds 1 to `readies`. */
export const pickTeamScenario: ScenarioDefinition = {
  ...pushBallScenario,
  name: 'test-pick-team',
  messages: { pickTeam: { payload: { team: { min: 0, max: 1 } } }, ready: {} },
  state: { ...pushBallScenario.state, lastPick: { kind: 'number', initial: -1 }, readies: { kind: 'number' } },
  build(ctx) {
    const inner = pushBallScenario.build(ctx);
    return {
      ...inner,
      onMessage(c, m) {
        if (m.name === 'pickTeam') c.setState('lastPick', m.playerId * 10 + m.payload.team);
        else c.setState('readies', (c.getState('readies') as number) + 1);
      },
    };
  },
};
