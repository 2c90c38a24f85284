// World limits: the sizes a PhysicsWorld is created with and the two fixed budgets Emscripten must never see
// overflow (it aborts the whole module): the 128 MiB WASM heap and Jolt's 10 MiB step temp allocator.
// Every coefficient below was measured on jolt-physics 1.1.0 (Jolt 5.6.0); docs/physics.md lists the runs.
import type { Vec3Like } from '../physics-data/vectors.ts';
import type { PhysicsInitOptions } from './jolt-backend.ts';

/** Options of PhysicsWorld.create: how to load Jolt plus the world's fixed limits. */
export interface PhysicsWorldOptions extends PhysicsInitOptions {
  /** Most bodies the world holds (Jolt's mMaxBodies); adding more throws. Default 10240, at most 65536. */
  maxBodies?: number;
  /** Body pairs Jolt's contact cache holds (mMaxBodyPairs). Default 16384. */
  maxBodyPairs?: number;
  /** Contact constraints solved per step (mMaxContactConstraints); extra contacts are dropped. Default 8192. */
  maxContactConstraints?: number;
  /** Free WASM heap kept in reserve; a creation that would eat into it throws. Default 8 MiB. */
  minFreeHeapBytes?: number;
  /** Gravity (m/s²); default (0, -9.81, 0). */
  gravity?: Vec3Like;
  /**
   * Build the world on its own Jolt module instance (its own 128 MB heap; see createJoltInstance) instead of the
   * process-wide one. The server gives every room one. Default false.
   */
  isolatedModule?: boolean;
  /** Build the world on this already loaded module (wins over isolatedModule). */
  jolt?: import('./jolt-backend.ts').JoltModule;
}

/** The resolved, validated limits of one world. */
export interface WorldLimits {
  maxBodies: number;
  maxBodyPairs: number;
  maxContactConstraints: number;
  minFreeHeapBytes: number;
}

/** Jolt's step temp allocator: a fixed 10 MiB in jolt-physics 1.1.0 (JoltSettings cannot change it). */
export const TEMP_ALLOCATOR_BYTES = 10 * 1024 * 1024;
// Temp bytes one step takes (measured: the largest settings that did not abort, then rounded up).
const TEMP_FIXED_BYTES = 160 * 1024; // 16384 in-flight body pairs × 8 B, plus bookkeeping
const TEMP_PER_CONTACT_BYTES = 500; // the contact constraint buffer is allocated whole every step (measured 482 B)
const TEMP_PER_BODY_BYTES = 64; // active-body, island and splitter arrays per active body (measured ≤ 50 B)
const TEMP_PER_CCD_BODY_BYTES = 176; // extra per active linear-cast (CCD) body (measured 144 B)
const TEMP_PER_CONSTRAINT_BYTES = 32; // per constraint (measured 20 B)
/** Temp bytes kept free for character updates and measurement noise. */
const TEMP_RESERVE_BYTES = 512 * 1024;

// WASM heap bytes one world takes at creation (measured: 10.62 MB + 33 B/body + 88 B/pair + 336 B/contact).
const WORLD_FIXED_BYTES = 10_700_000;
const WORLD_PER_BODY_BYTES = 36;
const WORLD_PER_BODY_PAIR_BYTES = 92;
const WORLD_PER_CONTACT_BYTES = 344;
/** Heap a new world must leave free (so its first bodies fit). */
const WORLD_CREATE_SPARE_BYTES = 2 * 1024 * 1024;

const MiB = 1024 * 1024;

function fmtMiB(bytes: number): string {
  return `${(bytes / MiB).toFixed(1)} MiB`;
}

/** Validates an optional integer option within [min, max]. */
function intOption(value: number | undefined, fallback: number, min: number, max: number, name: string): number {
  if (value === undefined) return fallback;
  if (typeof value !== 'number' || !Number.isInteger(value) || value < min || value > max) {
    throw new Error(`PhysicsWorld.create: ${name} must be an integer in [${min}, ${max}], got ${String(value)}`);
  }
  return value;
}

/** Temp bytes a step needs before any CCD body or constraint exists, with every body awake. */
function baseStepTempBytes(l: WorldLimits): number {
  return TEMP_FIXED_BYTES + TEMP_PER_CONTACT_BYTES * l.maxContactConstraints + TEMP_PER_BODY_BYTES * l.maxBodies + TEMP_RESERVE_BYTES;
}

/** Reads and checks the limits; throws when they could overflow the temp allocator in a step. */
export function resolveWorldLimits(opts: PhysicsWorldOptions): WorldLimits {
  const limits: WorldLimits = {
    maxBodies: intOption(opts.maxBodies, 10240, 1, 65536, 'maxBodies'),
    maxBodyPairs: intOption(opts.maxBodyPairs, 16384, 64, 65536, 'maxBodyPairs'),
    maxContactConstraints: intOption(opts.maxContactConstraints, 8192, 64, 20000, 'maxContactConstraints'),
    minFreeHeapBytes: intOption(opts.minFreeHeapBytes, 8 * MiB, 0, 64 * MiB, 'minFreeHeapBytes'),
  };
  const need = baseStepTempBytes(limits);
  if (need > TEMP_ALLOCATOR_BYTES) {
    throw new Error(
      `PhysicsWorld.create: maxContactConstraints ${limits.maxContactConstraints} with maxBodies ${limits.maxBodies} needs ~${fmtMiB(need)} ` +
        `of step memory, more than Jolt's fixed ${fmtMiB(TEMP_ALLOCATOR_BYTES)} temp allocator: lower one of them`,
    );
  }
  return limits;
}

/** WASM heap bytes a world with these limits takes when created. */
export function estimateWorldHeapBytes(l: WorldLimits): number {
  return WORLD_FIXED_BYTES + WORLD_PER_BODY_BYTES * l.maxBodies + WORLD_PER_BODY_PAIR_BYTES * l.maxBodyPairs + WORLD_PER_CONTACT_BYTES * l.maxContactConstraints;
}

/** Throws unless the heap can take a new world with these limits (Jolt would abort the module otherwise). */
export function ensureRoomForWorld(freeBytes: number, l: WorldLimits): void {
  const need = estimateWorldHeapBytes(l);
  if (freeBytes - need < WORLD_CREATE_SPARE_BYTES) {
    throw new Error(
      `PhysicsWorld.create: the WASM heap has ${fmtMiB(freeBytes)} free, a world with these limits needs ~${fmtMiB(need)} ` +
        `(+${fmtMiB(WORLD_CREATE_SPARE_BYTES)} spare): destroy another world or lower maxBodies / maxBodyPairs / maxContactConstraints`,
    );
  }
}

/** Throws unless the heap can take `bytes` more and still keep `minFreeBytes` in reserve. */
export function ensureHeapRoom(freeBytes: number, bytes: number, minFreeBytes: number, what: string): void {
  if (freeBytes - bytes < minFreeBytes) {
    throw new Error(
      `${what}: the WASM heap is nearly full (${fmtMiB(freeBytes)} free, ~${fmtMiB(bytes)} needed, ` +
        `${fmtMiB(minFreeBytes)} kept in reserve for stepping)`,
    );
  }
}

/** Saved state per body and per constraint, with room for contacts (measured 297-943 B per body). */
const STATE_BYTES_PER_BODY = 1200;
const STATE_BYTES_PER_CONSTRAINT = 256;

/**
 * Heap bytes a full state save (SaveState with contacts) into the in-memory buffer may take at its peak: the
 * buffer grows by doubling, so 2.5× the saved size.
 */
export function estimateStateSaveBytes(bodies: number, constraints: number): number {
  return Math.ceil(2.5 * (4096 + STATE_BYTES_PER_BODY * bodies + STATE_BYTES_PER_CONSTRAINT * constraints));
}

/** What grows a step's temp-memory need after creation. */
export type StepCost = 'ccdBody' | 'constraint';

/** Counts CCD bodies and constraints so no step can overflow the fixed temp allocator (it would abort). */
export class StepBudget {
  private readonly spareBytes: number;
  private usedBytes = 0;
  private ccdBodies = 0;
  private constraints = 0;

  constructor(limits: WorldLimits) {
    this.spareBytes = TEMP_ALLOCATOR_BYTES - baseStepTempBytes(limits);
  }

  private static cost(kind: StepCost): number {
    return kind === 'ccdBody' ? TEMP_PER_CCD_BODY_BYTES : TEMP_PER_CONSTRAINT_BYTES;
  }

  /** Takes one unit of `kind`, or throws a clear Error when a step could no longer fit. */
  reserve(kind: StepCost, what: string): void {
    const cost = StepBudget.cost(kind);
    if (this.usedBytes + cost > this.spareBytes) {
      throw new Error(
        `${what}: the world's step memory is spent (${this.ccdBodies} linear-cast bodies, ${this.constraints} constraints; ` +
          `Jolt's temp allocator is a fixed ${fmtMiB(TEMP_ALLOCATOR_BYTES)}): lower maxContactConstraints or maxBodies to make room`,
      );
    }
    this.usedBytes += cost;
    if (kind === 'ccdBody') this.ccdBodies++;
    else this.constraints++;
  }

  /** How many more units of `kind` fit (ignoring any other kind taken later). */
  room(kind: StepCost): number {
    return Math.max(0, Math.floor((this.spareBytes - this.usedBytes) / StepBudget.cost(kind)));
  }

  /** Gives back one unit of `kind`. */
  release(kind: StepCost): void {
    this.usedBytes -= StepBudget.cost(kind);
    if (kind === 'ccdBody') this.ccdBodies--;
    else this.constraints--;
  }
}
