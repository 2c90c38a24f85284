// The Jolt objects every character of one world can share instead of building its own on each join: the feet-origin
// capsule shape per size, the query filters per object layer, one body filter and one shape filter, and the
// ExtendedUpdateSettings per stair/floor-stick setting. Jolt only reads them, so sharing changes no result. Built on
// first use, freed when the world is destroyed.
import type { JoltModule } from './jolt-backend.ts';
import { makeBroadPhaseFilter, makeObjectLayerFilter } from './layers.ts';
import { worldInternals, type PhysicsWorld } from './physics-world.ts';

type J = JoltModule;

/** A query filter pair for one object layer. */
export interface CharacterFilters {
  readonly bp: InstanceType<J['DefaultBroadPhaseLayerFilter']>;
  readonly obj: InstanceType<J['DefaultObjectLayerFilter']>;
}

/** One world's shared character objects. */
export interface CharacterParts {
  /** The capsule of half-height `halfHeight` and `radius` standing on its origin (a reference the world holds). */
  shape(halfHeight: number, radius: number): InstanceType<J['Shape']>;
  filters(objectLayer: number): CharacterFilters;
  readonly bodyFilter: InstanceType<J['BodyFilter']>;
  readonly shapeFilter: InstanceType<J['ShapeFilter']>;
  /** Update settings walking stairs up to `stepUpMetres` and sticking to floors `stickMetres` below. */
  update(stepUpMetres: number, stickMetres: number): InstanceType<J['ExtendedUpdateSettings']>;
}

const PARTS = new WeakMap<PhysicsWorld, CharacterParts>();

/** The world's shared character objects (built on first call; the world frees them on destroy()). */
export function characterParts(world: PhysicsWorld): CharacterParts {
  const known = PARTS.get(world);
  if (known) return known;
  const J = world.jolt;
  const shapes = new Map<string, InstanceType<J['Shape']>>();
  const filters = new Map<number, CharacterFilters>();
  const updates = new Map<string, InstanceType<J['ExtendedUpdateSettings']>>();
  const parts: CharacterParts = {
    bodyFilter: new J.BodyFilter(), // owned by the parts; freed with the world
    shapeFilter: new J.ShapeFilter(), // owned by the parts; freed with the world
    shape(halfHeight, radius) {
      const key = `${halfHeight}/${radius}`;
      const cached = shapes.get(key);
      if (cached) return cached;
      const centreY = halfHeight + radius;
      const capsule = new J.CapsuleShapeSettings(halfHeight, radius); // owned by the decorated settings below
      const offset = new J.Vec3(0, centreY, 0); // copied, freed below
      const identity = new J.Quat(0, 0, 0, 1); // copied, freed below
      const shapeSettings = new J.RotatedTranslatedShapeSettings(offset, identity, capsule); // freed after Create()
      J.destroy(offset);
      J.destroy(identity);
      const result = shapeSettings.Create(); // static temporary: Clear()ed, never destroyed
      const shape = result.Get();
      shape.AddRef(); // the parts' reference, released with the world
      result.Clear();
      J.destroy(shapeSettings); // also releases the capsule settings it referenced
      shapes.set(key, shape);
      return shape;
    },
    filters(objectLayer) {
      let pair = filters.get(objectLayer);
      if (!pair) {
        pair = { bp: makeBroadPhaseFilter(J, world.filters, objectLayer), obj: makeObjectLayerFilter(J, world.filters, objectLayer) }; // owned by the parts
        filters.set(objectLayer, pair);
      }
      return pair;
    },
    update(stepUpMetres, stickMetres) {
      const key = `${stepUpMetres}/${stickMetres}`;
      let update = updates.get(key);
      if (!update) {
        update = new J.ExtendedUpdateSettings(); // owned by the parts; freed with the world
        update.mWalkStairsStepUp.Set(0, stepUpMetres, 0);
        update.mStickToFloorStepDown.Set(0, -stickMetres, 0);
        updates.set(key, update);
      }
      return update;
    },
  };
  PARTS.set(world, parts);
  worldInternals(world).disposers.add(() => {
    // Characters hold their own references to the shape; filters and settings are only read during their updates.
    for (const shape of shapes.values()) shape.Release();
    for (const pair of filters.values()) {
      J.destroy(pair.bp);
      J.destroy(pair.obj);
    }
    for (const update of updates.values()) J.destroy(update);
    J.destroy(parts.bodyFilter);
    J.destroy(parts.shapeFilter);
    PARTS.delete(world);
  });
  return parts;
}
