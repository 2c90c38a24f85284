// What the determinism-check page (page.ts) and its Node host (host.ts) exchange: the job it fetches and the raw
// hashes it posts back. Plain JSON.
import type { TickInputRecord } from '../../../shared/sim/types.ts';

/** One checkpoint made in Node for the page to restore and continue. */
export interface ResumeJob {
  scenario: string;
  seed: number;
  /** Simulation.saveCheckpointBytes() in Node, base64. */
  checkpointB64: string;
  /** The records to apply after restoring, in order. */
  records: TickInputRecord[];
  /** Index into records before which the page saves a fast checkpoint, and to which it rolls back at the end. */
  fastCheckpointAfter: number;
}

/** The job the page fetches from job.json. */
export interface SimCheckJob {
  /** The production build's physics chunk (client/physics/index.ts as built), relative to the page. */
  physicsChunk: string;
  /** The constants of a golden run (shared/sim/golden.ts; the page does not bundle that module, which loads Jolt). */
  golden: { seed: number; joinSpacingTicks: number; hashEveryTicks: number };
  resumes: ResumeJob[];
}

/** What the page saw after resuming one checkpoint. */
export interface ResumeResult {
  scenario: string;
  /** The simulation's tick right after restoring. */
  restoredTick: number;
  /** State hash after each record. */
  hashes: string[];
  /** Index of the first record re-applied after the fast rollback (-1: none). */
  rerunFrom: number;
  /** State hash after each re-applied record. */
  rerunHashes: string[];
}

/** What the page posts to /result. */
export interface SimCheckResult {
  userAgent: string;
  goldens: Array<{ scenario: string; ticks: number; hash: string; checkpoints: Array<{ tick: number; hash: string }> }>;
  resumes: ResumeResult[];
  /** Set when the page failed (message and stack); the other fields then hold what it got through. */
  error: string | null;
}
