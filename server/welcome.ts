// The welcome a joining (or resuming) client gets: the room's scenario, its snapshot format (one per room), the static
// scene and every live non-static body, and the player's resume token; plus the snapshot encoder that starts from it.
import { PROTOCOL_VERSION, SnapshotEncoder, snapshotFormatSpec, type GameSchemaInfo, type WelcomeMessage } from '../shared/protocol/index.ts';
import type { BodyDescriptor } from '../shared/sim/types.ts';
import { TICK_RATE_HZ } from '../shared/tick-rate.ts';
import type { Room } from './room.ts';

/** Every live body snapshots will carry: non-static ones and statics spawned after the scene was built. */
function liveDynamicDescriptors(room: Room): BodyDescriptor[] {
  const read = room.sim.readBodyStates();
  const out: BodyDescriptor[] = [];
  for (let i = 0; i < read.count; i++) {
    if (room.isSceneStatic(read.ids[i])) continue;
    const d = room.sim.bodyDescriptor(read.ids[i]);
    if (d) out.push(d);
  }
  return out;
}

/** The scenario's game schema for the welcome (nothing when it declares none). */
function gameSchema(room: Room): { game?: GameSchemaInfo } {
  const game: GameSchemaInfo = {};
  const input = room.sim.gameInputFields ?? [];
  const state = room.sim.gameStateFields ?? [];
  if (input.length > 0) game.input = input;
  if (state.length > 0) game.state = state.map((f) => ({ name: f.name, kind: f.kind, maxLength: f.maxLength }));
  const messages = room.sim.gameMessageKinds ?? [];
  if (messages.length > 0) game.messages = messages;
  return Object.keys(game).length > 0 ? { game } : {};
}

/** The welcome for `playerId`, and a snapshot encoder that counts the welcome's descriptors as delivered. */
export function buildWelcome(room: Room, playerId: number, resume: { token: string | null; graceMs: number; resumed: boolean }): { message: WelcomeMessage; encoder: SnapshotEncoder } {
  const format = room.snapshots.format;
  const encoder = new SnapshotEncoder(format);
  const dynamicBodies = liveDynamicDescriptors(room);
  encoder.markDescriptorsKnown(dynamicBodies.map((d) => d.id));
  const message: WelcomeMessage = {
    type: 'welcome',
    protocolVersion: PROTOCOL_VERSION,
    playerId,
    roomId: room.id,
    tick: room.sim.tick,
    tickRateHz: TICK_RATE_HZ,
    snapshotRateHz: room.snapshotRateHz,
    scenario: { name: room.scenarioName, description: room.description, params: { ...room.params }, bounds: room.bounds, ...gameSchema(room) },
    snapshotFormat: snapshotFormatSpec(format),
    staticBodies: room.staticDescriptors(),
    dynamicBodies,
    resumeToken: resume.token,
    resumeGraceMs: resume.graceMs,
    resumed: resume.resumed,
    netMode: room.netMode,
    inputDelayTicks: 0,
  };
  return { message, encoder };
}
