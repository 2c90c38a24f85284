// The two bandwidth baselines, fed the same world state our codec gets: plain msgpackr of every moving body's float
// pose per snapshot, and @colyseus/schema delta patches of a Schema with a MapSchema of bodies (its encoder sends only
// fields whose value changed since its previous patch, over a reliable ordered stream).
import { Encoder, schema, t } from '@colyseus/schema';
import { FLOAT32_OPTIONS, Packr } from 'msgpackr';
import { ServerOpcode, type SnapshotView } from '../../shared/protocol/index.ts';

// A careful naive baseline: arrays (no keys) and float32 numbers (5 bytes each) instead of msgpack's default float64.
const naivePackr = new Packr({ useRecords: false, useFloat32: FLOAT32_OPTIONS.ALWAYS });

/** One naive snapshot message: [opcode, tick, [[id, px, py, pz, qx, qy, qz, qw]…], [[playerId, x, y, z, yaw, pitch]…]]. */
export function naiveSnapshotBytes(view: SnapshotView): number {
  const bodies: number[][] = [];
  for (let i = 0; i < view.ids.length; i++) {
    const p = i * 3;
    const q = i * 4;
    bodies.push([view.ids[i], view.positions[p], view.positions[p + 1], view.positions[p + 2], view.rotations[q], view.rotations[q + 1], view.rotations[q + 2], view.rotations[q + 3]]);
  }
  const characters = view.characters.map((c) => [c.playerId, c.position.x, c.position.y, c.position.z, c.yaw, c.pitch]);
  return naivePackr.pack([ServerOpcode.Snapshot, view.tick, bodies, characters]).length;
}

const BodyState = schema(
  { x: t.float32(), y: t.float32(), z: t.float32(), qx: t.float32(), qy: t.float32(), qz: t.float32(), qw: t.float32(), atRest: t.boolean() },
  'BodyState',
);
const CharacterState = schema({ x: t.float32(), y: t.float32(), z: t.float32(), yaw: t.float32(), pitch: t.float32(), buttons: t.uint8() }, 'CharacterState');
const WorldState = schema({ tick: t.uint32(), bodies: t.map(BodyState), characters: t.map(CharacterState) }, 'WorldState');
type BodyInstance = InstanceType<typeof BodyState>;
type CharacterInstance = InstanceType<typeof CharacterState>;

// A full state of ~1000 bodies is ~40 KB; size the shared buffer for it up front (Colyseus warns when it grows).
Encoder.BUFFER_SIZE = 256 * 1024;

/** Bytes Colyseus adds around a patch: its ROOM_STATE_PATCH protocol byte. */
export const COLYSEUS_ENVELOPE_BYTES = 1;

/** A Colyseus room's state replication for one snapshot rate: apply a world view, get the patch size. */
export class ColyseusStream {
  private readonly state = new WorldState();
  private readonly encoder = new Encoder(this.state);
  private started = false;

  /** Applies a snapshot's state and returns the size of the patch a client receives (the full state the first time). */
  update(view: SnapshotView): number {
    const s = this.state;
    s.tick = view.tick;
    const seen = new Set<string>();
    for (let i = 0; i < view.ids.length; i++) {
      const key = String(view.ids[i]);
      seen.add(key);
      let b = s.bodies.get(key) as BodyInstance | undefined;
      if (!b) {
        b = new BodyState();
        s.bodies.set(key, b);
      }
      const p = i * 3;
      const q = i * 4;
      b.x = view.positions[p];
      b.y = view.positions[p + 1];
      b.z = view.positions[p + 2];
      b.qx = view.rotations[q];
      b.qy = view.rotations[q + 1];
      b.qz = view.rotations[q + 2];
      b.qw = view.rotations[q + 3];
      b.atRest = view.atRest[i] === 1;
    }
    for (const key of [...s.bodies.keys()]) if (!seen.has(key)) s.bodies.delete(key);
    const chars = new Set<string>();
    for (const c of view.characters) {
      const key = String(c.playerId);
      chars.add(key);
      let ch = s.characters.get(key) as CharacterInstance | undefined;
      if (!ch) {
        ch = new CharacterState();
        s.characters.set(key, ch);
      }
      ch.x = c.position.x;
      ch.y = c.position.y;
      ch.z = c.position.z;
      ch.yaw = c.yaw;
      ch.pitch = c.pitch;
      ch.buttons = c.buttons;
    }
    for (const key of [...s.characters.keys()]) if (!chars.has(key)) s.characters.delete(key);
    const bytes = this.started ? this.encoder.encode() : this.encoder.encodeAll();
    this.started = true;
    const size = bytes.length;
    this.encoder.discardChanges();
    return size === 0 ? 0 : size + COLYSEUS_ENVELOPE_BYTES;
  }
}
