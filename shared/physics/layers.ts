// The collision layer/mask scheme (seed §25.5): named group bits, the symmetric rule, and the Jolt filter objects
// that implement it. World goes to the non-moving broad-phase layer, every other group to the moving one.
import type { JoltModule } from './jolt-backend.ts';

/** Named collision groups; a body has a `layer` (groups it is in) and a `mask` (groups it collides with). */
export const CollisionLayer = {
  World: 1 << 0, // static level geometry (non-moving broad phase)
  Player: 1 << 1,
  Enemy: 1 << 2,
  Bullet: 1 << 3,
  Prop: 1 << 4, // dynamic debris: the default for dynamic bodies
  Trigger: 1 << 5, // sensor / trigger volumes
  All: 0xffff,
} as const;

export type CollisionLayerName = keyof typeof CollisionLayer;

/** Groups routed to the non-moving broad-phase tree. */
export const STATIC_GROUPS = CollisionLayer.World;
/** Every other group: the moving broad-phase tree. */
export const DYNAMIC_GROUPS = CollisionLayer.All & ~CollisionLayer.World;

const BP_NON_MOVING = 0;
const BP_MOVING = 1;
const NUM_BROAD_PHASE_LAYERS = 2;

/** The symmetric rule, in plain JS: two bodies interact only if each one's layer is in the other's mask. */
export function layersInteract(layerA: number, maskA: number, layerB: number, maskB: number): boolean {
  return (layerA & maskB) !== 0 && (layerB & maskA) !== 0;
}

/** Checks a layer or mask value: a non-zero integer within the 16 group bits. */
export function assertGroupBits(value: number, what: string): void {
  if (!Number.isInteger(value) || value <= 0 || value > CollisionLayer.All) {
    throw new Error(`${what} must be a non-zero integer of CollisionLayer bits (1..0xffff), got ${String(value)}`);
  }
}

/** The three filter objects a JoltSettings needs; JoltInterface takes ownership of them. */
export interface LayerFilters {
  objectLayerPairFilter: InstanceType<JoltModule['ObjectLayerPairFilterMask']>;
  broadPhaseLayerInterface: InstanceType<JoltModule['BroadPhaseLayerInterfaceMask']>;
  objectVsBroadPhaseLayerFilter: InstanceType<JoltModule['ObjectVsBroadPhaseLayerFilterMask']>;
}

/** Builds the mask filters. The caller hands all three to JoltSettings (JoltInterface then owns them). */
export function createLayerFilters(J: JoltModule): LayerFilters {
  const objectLayerPairFilter = new J.ObjectLayerPairFilterMask(); // owned by JoltInterface once in JoltSettings
  const broadPhaseLayerInterface = new J.BroadPhaseLayerInterfaceMask(NUM_BROAD_PHASE_LAYERS); // owned by JoltInterface
  const bpNonMoving = new J.BroadPhaseLayer(BP_NON_MOVING); // copied by ConfigureLayer, freed below
  const bpMoving = new J.BroadPhaseLayer(BP_MOVING); // copied by ConfigureLayer, freed below
  broadPhaseLayerInterface.ConfigureLayer(bpNonMoving, STATIC_GROUPS, 0);
  broadPhaseLayerInterface.ConfigureLayer(bpMoving, DYNAMIC_GROUPS, 0);
  J.destroy(bpNonMoving);
  J.destroy(bpMoving);
  const objectVsBroadPhaseLayerFilter = new J.ObjectVsBroadPhaseLayerFilterMask(broadPhaseLayerInterface); // owned by JoltInterface
  return { objectLayerPairFilter, broadPhaseLayerInterface, objectVsBroadPhaseLayerFilter };
}

/** Packs (group, mask) into one Jolt ObjectLayer. */
export function packObjectLayer(J: JoltModule, group: number, mask: number): number {
  return J.ObjectLayerPairFilterMask.prototype.sGetObjectLayer(group, mask);
}

/** A query filter honouring the mask rule for a querying object layer. Caller destroys it. */
export function makeObjectLayerFilter(
  J: JoltModule,
  filters: LayerFilters,
  objectLayer: number,
): InstanceType<JoltModule['DefaultObjectLayerFilter']> {
  return new J.DefaultObjectLayerFilter(filters.objectLayerPairFilter, objectLayer); // caller owns
}

/** A broad-phase query filter for a querying object layer. Caller destroys it. */
export function makeBroadPhaseFilter(
  J: JoltModule,
  filters: LayerFilters,
  objectLayer: number,
): InstanceType<JoltModule['DefaultBroadPhaseLayerFilter']> {
  return new J.DefaultBroadPhaseLayerFilter(filters.objectVsBroadPhaseLayerFilter, objectLayer); // caller owns
}
