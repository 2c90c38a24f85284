// Ball Goals: players push (and kick) a ball into the other team's goal. A complete game on the public API: a
// scenario with a custom "kick" button, a replicated score, goals that are sensor volumes and a "resetBall" message.
import { CollisionLayer, defineScenario, detCos, detSin } from '../../api/index.ts';

/** Where the ball starts and goes back to after a goal. */
export const KICK_OFF = { x: 0, y: 0.4, z: 0 } as const;
/** How close (m, on the ground) a player must be to kick the ball. */
export const KICK_REACH_METRES = 1.8;
/** The ball's speed straight after a kick (m/s), along the kicker's facing, and its upward part. */
const KICK_SPEED = 9;
const KICK_LIFT = 2;

const PITCH = { halfX: 10, halfZ: 16 } as const;
const WALL = { height: 1.5, thickness: 0.5 } as const;
/** Goal mouths at either end: the ball entering red's goal (−z end) scores for blue, and the other way round. */
const GOAL = { halfX: 2.5, halfY: 1.2, halfDepth: 1, z: PITCH.halfZ - 1 } as const;

export const scenario = defineScenario({
  name: 'ball-goals',
  description: 'Two teams push a ball into the other goal; press kick near the ball to shoot.',
  bounds: { min: { x: -20, y: -5, z: -25 }, max: { x: 20, y: 30, z: 25 } },
  golden: { ticks: 600, bots: 2 },
  input: { kick: { kind: 'button' } },
  state: {
    scoreRed: { kind: 'number' },
    scoreBlue: { kind: 'number' },
    lastGoal: { kind: 'string', maxLength: 4 },
  },
  messages: { resetBall: {} },
  // About 0.1 ms a tick with 4 players (p50 on a loaded 2-core machine), so `--net-mode auto` serves predict mode.
  tickCostMs: 0.3,
  build(ctx) {
    const grey = [0.35, 0.38, 0.4] as const;
    ctx.spawn({ kind: 'box', halfExtents: { x: PITCH.halfX + 1, y: 0.5, z: PITCH.halfZ + 1 } }, { x: 0, y: -0.5, z: 0 }, null, { motion: 'static', color: [0.2, 0.45, 0.25], name: 'pitch' });
    for (const side of [-1, 1]) {
      ctx.spawn({ kind: 'box', halfExtents: { x: WALL.thickness, y: WALL.height, z: PITCH.halfZ } }, { x: side * (PITCH.halfX + WALL.thickness), y: WALL.height, z: 0 }, null, { motion: 'static', color: grey, name: 'side wall' });
      ctx.spawn({ kind: 'box', halfExtents: { x: PITCH.halfX, y: WALL.height, z: WALL.thickness } }, { x: 0, y: WALL.height, z: side * (PITCH.halfZ + WALL.thickness) }, null, { motion: 'static', color: grey, name: 'end wall' });
    }
    const goal = (z: number, color: readonly [number, number, number], name: string): number =>
      ctx.spawn({ kind: 'box', halfExtents: { x: GOAL.halfX, y: GOAL.halfY, z: GOAL.halfDepth } }, { x: 0, y: GOAL.halfY, z }, null, {
        motion: 'static',
        isSensor: true,
        layer: CollisionLayer.Trigger,
        mask: CollisionLayer.Prop, // the ball (dynamic bodies are props), not the players
        color,
        name,
      }).id;
    const redGoal = goal(-GOAL.z, [0.9, 0.25, 0.2], 'red goal');
    const blueGoal = goal(GOAL.z, [0.2, 0.4, 0.95], 'blue goal');
    const ball = ctx.spawn({ kind: 'sphere', radius: 0.4 }, KICK_OFF, null, { motion: 'dynamic', massKg: 0.5, color: [0.95, 0.95, 0.9], name: 'ball' }).id;

    const resetBall = (c: typeof ctx): void => {
      c.world.setPosition(ball, KICK_OFF);
      c.world.setLinearVelocity(ball, { x: 0, y: 0, z: 0 });
      c.world.setAngularVelocity(ball, { x: 0, y: 0, z: 0 });
    };

    return {
      // Even players (red) start on the +z half facing −z; odd players (blue) on the −z half.
      spawnPoint: (n) => (n % 2 === 0 ? { x: ((n / 2) % 3) * 2, y: 0.05, z: 2.5 } : { x: -(((n - 1) / 2) % 3) * 2 - 2, y: 0.05, z: -2.5 }),
      onMessage(c, msg) {
        if (msg.name === 'resetBall') resetBall(c);
      },
      onTick(c) {
        // Every player holding kick within reach kicks along its facing; in player order, so the last one wins.
        const at = c.world.getBody(ball)!.position();
        for (const ch of c.characters()) {
          if (c.gameInput(ch.playerId).kick !== 1) continue;
          const dx = at.x - ch.position.x;
          const dz = at.z - ch.position.z;
          if (dx * dx + dz * dz > KICK_REACH_METRES * KICK_REACH_METRES) continue;
          c.world.setLinearVelocity(ball, { x: -detSin(ch.yaw) * KICK_SPEED, y: KICK_LIFT, z: -detCos(ch.yaw) * KICK_SPEED });
        }
      },
      onEvents(c, events) {
        for (const e of events) {
          if (e.type !== 'sensorEnter' || e.bodyId !== ball) continue;
          if (e.sensorId !== redGoal && e.sensorId !== blueGoal) continue;
          const scorer = e.sensorId === redGoal ? 'blue' : 'red';
          const key = scorer === 'blue' ? 'scoreBlue' : 'scoreRed';
          c.setState(key, (c.getState(key) as number) + 1);
          c.setState('lastGoal', scorer);
          c.emit('goal', scorer === 'blue' ? 1 : 0);
          resetBall(c);
        }
      },
    };
  },
});
