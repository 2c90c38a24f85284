// Test fixture: a complete welcome message (scenario, format, static and dynamic bodies) shared by protocol tests.
import { PROTOCOL_VERSION } from '../../../shared/protocol/opcodes.ts';
import type { WelcomeMessage } from '../../../shared/protocol/server-messages.ts';

/** A welcome as a cubes-901 room would send it. */
export const sampleWelcome: WelcomeMessage = {
  type: 'welcome',
  protocolVersion: PROTOCOL_VERSION,
  playerId: 3,
  roomId: 'default',
  tick: 1234,
  tickRateHz: 60,
  snapshotRateHz: 30,
  scenario: { name: 'cubes-901', description: '900 cubes and a rolling one', params: { count: 900, spacing: 1.25 }, bounds: { min: { x: -50, y: -5, z: -50 }, max: { x: 50, y: 45, z: 50 } } },
  snapshotFormat: { positionSteps: [50000, 25000, 50000], rotationBits: 10 },
  staticBodies: [{ id: 0, shape: { kind: 'box', halfExtents: { x: 50, y: 0.5, z: 50 } }, color: [0.3, 0.3, 0.3], motion: 'static', hidden: false, position: { x: 0, y: -0.5, z: 0 }, rotation: { x: 0, y: 0, z: 0, w: 1 } }],
  dynamicBodies: [{ id: 1, shape: { kind: 'sphere', radius: 0.5 }, color: [1, 0, 0], motion: 'dynamic', hidden: false, playerId: 3, position: { x: 0, y: 3, z: 0 }, rotation: { x: 0, y: 0, z: 0, w: 1 } }],
  resumeToken: 'Zm9yLXRlc3RzLW9ubHktMzItYnl0ZXMtb2YtcmFuZG9t',
  resumeGraceMs: 30_000,
  resumed: false,
  netMode: 'snapshot',
  inputDelayTicks: 0,
};
