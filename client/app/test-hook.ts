// The read-only test hook `window.__taos`: every read returns a fresh, frozen snapshot of the page's state, so
// browser tests can observe the client but never change it.
import type { AdapterSummary } from '../render/gpu-context.ts';
import type { PredictionStats } from '../../sdk/index.ts';
import type { FrameTimingSummary } from './frame-timer.ts';
import type { KeyToMotion } from './motion-meter.ts';

/** A body as drawn this frame (interpolated pose). */
export interface HookBody {
  id: number;
  position: [number, number, number];
  rotation: [number, number, number, number];
}

/** A character as drawn this frame. */
export interface HookCharacter {
  playerId: number;
  bodyId: number;
  /** Feet position (m), interpolated. */
  position: [number, number, number];
}

/** Everything the hook exposes. */
export interface TaosState {
  /** 'start' | 'connecting' | 'playing' | 'spectating' | 'closed' | 'error' | 'gallery'. */
  page: string;
  connected: boolean;
  playerId: number | null;
  roomId: string | null;
  scenario: string | null;
  /** Latest server tick received. */
  serverTick: number;
  /** Tick being drawn (fractional: interpolated). */
  renderTick: number;
  framesRendered: number;
  /** Milliseconds from navigation start to the first frame with the world in it. */
  firstFrameMs: number | null;
  /** Milliseconds from navigation start to the WebGPU device being ready, and to the server's welcome. */
  startup: { gpuReadyMs: number | null; welcomeMs: number | null };
  frameTiming: FrameTimingSummary;
  adapter: AdapterSummary | null;
  /** The message shown to the user when something failed. */
  error: string | null;
  bodies: HookBody[];
  characters: HookCharacter[];
  /** Sensor bodies, whether something is inside each, and whether it is drawn lit. */
  sensors: Array<{ sensorId: number; occupied: boolean; lit: boolean }>;
  /** Recent event lines as shown in the feed. */
  events: string[];
  net: {
    rttMs: number;
    snapshotsPerSecond: number;
    kbpsIn: number;
    interpolationDelayMs: number;
    bufferDepth: number;
    inputLeadTicks: number;
    /** The room's net mode as the welcome said (null before one). */
    netMode: 'snapshot' | 'predict' | null;
    /** Predicted play's numbers (sdk stats().prediction) while the page runs the room's simulation; else null. */
    prediction: PredictionStats | null;
  };
  /** The last key → own motion measured (client/app/motion-meter.ts), and how many were measured. */
  keyToMotion: (KeyToMotion & { count: number }) | null;
  /** The camera of the last frame (null before one), with the canvas size it was drawn at (device pixels). */
  camera: { eye: number[]; target: number[]; fovYRadians: number; nearMetres: number; farMetres: number; widthPx: number; heightPx: number } | null;
}

function deepFreeze<T>(value: T): T {
  if (value && typeof value === 'object' && !Object.isFrozen(value)) {
    Object.freeze(value);
    for (const v of Object.values(value as Record<string, unknown>)) deepFreeze(v);
  }
  return value;
}

/** Installs `window.__taos` reading from `read` (called on every access). */
export function installTestHook(read: () => TaosState): void {
  Object.defineProperty(globalThis, '__taos', {
    configurable: true,
    enumerable: false,
    get: () => deepFreeze(read()),
    set: () => {
      throw new Error('window.__taos is read-only');
    },
  });
}
