// Public surface of the physics layer: the only entry point other folders import from shared/physics. It also
// re-exports the plain data of shared/physics-data/ (shapes, vectors, body-state layout) that its API speaks.
export { BodyFlag, BODY_STATE_STRIDE } from '../physics-data/body-state.ts';
export { validateShapeSpec, type CompoundPart, type ShapeKind, type ShapeSpec } from '../physics-data/shape-spec.ts';
export { IDENTITY_QUAT, type QuatLike, type Vec3Like } from '../physics-data/vectors.ts';
export { BodyHandle, type BodyRole, type JoltBody } from './body-handle.ts';
export type { BodyIdAllocatorState } from './body-id-allocator.ts';
export { CharacterController, type CharacterOptions, type GroundState } from './character-controller.ts';
export { distanceLink, hingeLink, pointLink, sliderLink } from './constraints.ts';
export { createJoltInstance, getJolt, initializePhysics, isPhysicsInitialized, loadJolt, setDefaultPhysicsInitOptions, type JoltModule, type PhysicsInitOptions } from './jolt-backend.ts';
export { CollisionLayer, layersInteract, makeBroadPhaseFilter, makeObjectLayerFilter, type CollisionLayerName } from './layers.ts';
export { PhysicsWorld, type PhysicsWorldOptions } from './physics-world.ts';
export { type RayHit } from './queries.ts';
export { type SensorEvent } from './sensors.ts';
export { buildShape, estimateShapeBytes } from './shapes.ts';
export { FastStateBuffer, restoreStateBytes, saveStateBytes, type JoltStateRecorder } from './state-recorder.ts';
export type { BodyOptions, MotionKind, MotionQualityKind, SensorCallbacks } from './types.ts';
