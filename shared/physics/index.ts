// Public surface of the physics layer: the only entry point other folders import from shared/physics.
export { BodyFlag, BodyHandle, BODY_STATE_STRIDE, type BodyRole, type JoltBody } from './body-handle.ts';
export { CharacterController, type CharacterOptions, type GroundState } from './character-controller.ts';
export { distanceLink, hingeLink, pointLink, sliderLink } from './constraints.ts';
export { createJoltInstance, getJolt, initializePhysics, isPhysicsInitialized, loadJolt, setDefaultPhysicsInitOptions, type JoltModule, type PhysicsInitOptions } from './jolt-backend.ts';
export { CollisionLayer, layersInteract, makeBroadPhaseFilter, makeObjectLayerFilter, type CollisionLayerName } from './layers.ts';
export { FIXED_DT_SECONDS, PhysicsWorld, type PhysicsWorldOptions } from './physics-world.ts';
export { type RayHit } from './queries.ts';
export { type SensorEvent } from './sensors.ts';
export { buildShape, estimateShapeBytes, validateShapeSpec, type CompoundPart, type ShapeKind, type ShapeSpec } from './shapes.ts';
export { FastStateBuffer, restoreStateBytes, saveStateBytes, type JoltStateRecorder } from './state-recorder.ts';
export { IDENTITY_QUAT, type BodyOptions, type MotionKind, type MotionQualityKind, type QuatLike, type SensorCallbacks, type Vec3Like } from './types.ts';
