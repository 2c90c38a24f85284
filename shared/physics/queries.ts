// Ray casts (seed §25.9): closest hit with point, body id, normal and fraction; plus an allocation-free rayDownY
// that reuses cached Jolt scratch objects. Rays ignore the Trigger group (sensors are not surfaces).
import { checkVec3 } from '../physics-data/shape-spec.ts';
import type { Vec3Like } from '../physics-data/vectors.ts';
import type { JoltModule } from './jolt-backend.ts';
import { CollisionLayer, makeBroadPhaseFilter, makeObjectLayerFilter, packObjectLayer } from './layers.ts';
import type { BodyHandle } from './body-handle.ts';
import type { PhysicsWorld } from './physics-world.ts';

/** The nearest hit of a ray. */
export interface RayHit {
  /** World-space hit point (m). */
  point: Vec3Like;
  /** Stable id of the body hit (undefined if it is not a tracked body). */
  bodyId: number | undefined;
  /** World-space surface normal at the hit. */
  normal: Vec3Like;
  /** Distance along the ray as a fraction of `direction`'s length, in [0, 1]. */
  fraction: number;
}

type J = JoltModule;
const QUERY_MASK_ALL = CollisionLayer.All & ~CollisionLayer.Trigger;

/** Cached Jolt query objects for one world, freed by dispose(). */
export class RayQueries {
  private readonly J: J;
  private readonly world: PhysicsWorld;
  private readonly bodyByJoltId: (joltId: number) => BodyHandle | undefined;
  private readonly settings: InstanceType<J['RayCastSettings']>;
  private readonly bodyFilter: InstanceType<J['BodyFilter']>;
  private readonly shapeFilter: InstanceType<J['ShapeFilter']>;
  private readonly filters: { bp: InstanceType<J['DefaultBroadPhaseLayerFilter']>; obj: InstanceType<J['DefaultObjectLayerFilter']> }[];
  private readonly origin: InstanceType<J['RVec3']>;
  private readonly direction: InstanceType<J['Vec3']>;
  private readonly ray: InstanceType<J['RRayCast']>;
  private readonly collector: InstanceType<J['CastRayClosestHitCollisionCollector']>;

  /** `bodyByJoltId` maps a hit's Jolt BodyID to the world's handle. */
  constructor(world: PhysicsWorld, bodyByJoltId: (joltId: number) => BodyHandle | undefined) {
    const J = world.jolt;
    this.J = J;
    this.world = world;
    this.bodyByJoltId = bodyByJoltId;
    this.settings = new J.RayCastSettings(); // owned here, freed in dispose()
    this.bodyFilter = new J.BodyFilter(); // accept-all; owned here
    this.shapeFilter = new J.ShapeFilter(); // accept-all; owned here
    const all = packObjectLayer(J, CollisionLayer.All, QUERY_MASK_ALL);
    const staticOnly = packObjectLayer(J, CollisionLayer.All, CollisionLayer.World);
    this.filters = [all, staticOnly].map((layer) => ({
      bp: makeBroadPhaseFilter(J, world.filters, layer), // owned here
      obj: makeObjectLayerFilter(J, world.filters, layer), // owned here
    }));
    this.origin = new J.RVec3(0, 0, 0); // scratch, owned here
    this.direction = new J.Vec3(0, -1, 0); // scratch, owned here
    this.ray = new J.RRayCast(this.origin, this.direction); // scratch, owned here
    this.collector = new J.CastRayClosestHitCollisionCollector(); // scratch, owned here
  }

  private cast(ox: number, oy: number, oz: number, dx: number, dy: number, dz: number, staticOnly: boolean): boolean {
    this.ray.mOrigin.Set(ox, oy, oz);
    this.ray.mDirection.Set(dx, dy, dz);
    this.collector.Reset();
    const f = this.filters[staticOnly ? 1 : 0];
    this.world.system.GetNarrowPhaseQuery().CastRay(this.ray, this.settings, this.collector, f.bp, f.obj, this.bodyFilter, this.shapeFilter);
    return this.collector.HadHit();
  }

  /** Closest hit along origin + t·direction (t in [0, 1]; |direction| is the reach), or null. */
  rayCast(origin: Vec3Like, direction: Vec3Like, staticOnly = false): RayHit | null {
    checkVec3(origin, 'rayCast', 'origin');
    checkVec3(direction, 'rayCast', 'direction');
    if (direction.x === 0 && direction.y === 0 && direction.z === 0) throw new Error('rayCast: direction must be non-zero');
    if (!this.cast(origin.x, origin.y, origin.z, direction.x, direction.y, direction.z, staticOnly)) return null;
    const J = this.J;
    const hit = this.collector.mHit;
    const fraction = hit.mFraction;
    const point = { x: origin.x + direction.x * fraction, y: origin.y + direction.y * fraction, z: origin.z + direction.z * fraction };
    const handle = this.bodyByJoltId(hit.mBodyID.GetIndexAndSequenceNumber());
    let normal: Vec3Like = { x: -direction.x, y: -direction.y, z: -direction.z };
    if (handle && !handle.removed) {
      const p = new J.RVec3(point.x, point.y, point.z); // copied by the call, freed below
      const n = handle.raw.GetWorldSpaceSurfaceNormal(hit.mSubShapeID2, p); // a reused temporary
      normal = { x: n.GetX(), y: n.GetY(), z: n.GetZ() };
      J.destroy(p);
    } else {
      const len = Math.sqrt(normal.x * normal.x + normal.y * normal.y + normal.z * normal.z);
      normal = { x: normal.x / len, y: normal.y / len, z: normal.z / len };
    }
    return { point, bodyId: handle?.id, normal, fraction };
  }

  /** Height of the first surface straight below (x, y, z) within `dist` metres, or null. Allocates nothing. */
  rayDownY(x: number, y: number, z: number, dist: number, staticOnly = false): number | null {
    if (!Number.isFinite(x) || !Number.isFinite(y) || !Number.isFinite(z) || !Number.isFinite(dist) || dist <= 0) {
      throw new Error(`rayDownY: need finite x, y, z and dist > 0, got (${x}, ${y}, ${z}, ${dist})`);
    }
    if (!this.cast(x, y, z, 0, -dist, 0, staticOnly)) return null;
    return y - dist * this.collector.mHit.mFraction;
  }

  /** Frees every cached Jolt object. */
  dispose(): void {
    const J = this.J;
    for (const f of this.filters) {
      J.destroy(f.bp);
      J.destroy(f.obj);
    }
    J.destroy(this.collector);
    J.destroy(this.ray);
    J.destroy(this.origin);
    J.destroy(this.direction);
    J.destroy(this.shapeFilter);
    J.destroy(this.bodyFilter);
    J.destroy(this.settings);
  }
}
