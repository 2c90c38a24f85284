// Jolt state I/O: the fast in-memory form (StateRecorderImpl, opaque bytes inside WASM) and the byte form
// (StateRecorderJS, copied out to a Uint8Array for disk and the wire). Both are owned by their creator.
import type { JoltModule } from './jolt-backend.ts';
import type { PhysicsWorld } from './physics-world.ts';

type J = JoltModule;
/** Any Jolt state recorder. */
export type JoltStateRecorder = InstanceType<J['StateRecorder']>;

/** A growable byte sink used while Jolt writes state. */
class ByteSink {
  bytes = new Uint8Array(1024);
  length = 0;
  write(src: Uint8Array): void {
    if (this.length + src.length > this.bytes.length) {
      const grown = new Uint8Array(Math.max(this.bytes.length * 2, this.length + src.length));
      grown.set(this.bytes.subarray(0, this.length));
      this.bytes = grown;
    }
    this.bytes.set(src, this.length);
    this.length += src.length;
  }
}

/** Runs `save` against a JS recorder and returns the bytes Jolt wrote (a fresh copy). */
export function saveStateBytes(Jm: J, save: (recorder: JoltStateRecorder) => void): Uint8Array {
  const sink = new ByteSink();
  const recorder = new Jm.StateRecorderJS(); // freed below
  recorder.WriteBytes = (ptr: number, n: number) => sink.write(Jm.HEAPU8.subarray(ptr, ptr + n));
  recorder.ReadBytes = () => {
    throw new Error('saveStateBytes: recorder is write-only');
  };
  recorder.IsEOF = () => false;
  recorder.IsFailed = () => false;
  try {
    save(recorder);
  } finally {
    Jm.destroy(recorder);
  }
  return sink.bytes.slice(0, sink.length);
}

/**
 * Runs `restore` against a JS recorder that reads `bytes`. Returns false (and restores nothing further) if
 * Jolt asked for more bytes than there are; `restore`'s own return value is and-ed in.
 */
export function restoreStateBytes(Jm: J, bytes: Uint8Array, restore: (recorder: JoltStateRecorder) => boolean | void): boolean {
  let offset = 0;
  let failed = false;
  const recorder = new Jm.StateRecorderJS(); // freed below
  recorder.ReadBytes = (ptr: number, n: number) => {
    if (offset + n > bytes.length) {
      failed = true;
      Jm.HEAPU8.fill(0, ptr, ptr + n);
      return;
    }
    Jm.HEAPU8.set(bytes.subarray(offset, offset + n), ptr);
    offset += n;
  };
  recorder.WriteBytes = () => {
    throw new Error('restoreStateBytes: recorder is read-only');
  };
  recorder.IsEOF = () => offset >= bytes.length;
  recorder.IsFailed = () => failed;
  try {
    const ok = restore(recorder);
    return ok !== false && !failed;
  } finally {
    Jm.destroy(recorder);
  }
}

/** The fast in-memory form: a StateRecorderImpl kept on the WASM heap. Call dispose() when done. */
export class FastStateBuffer {
  private readonly J: J;
  readonly recorder: InstanceType<J['StateRecorderImpl']>;
  private disposed = false;

  constructor(Jm: J) {
    this.J = Jm;
    this.recorder = new Jm.StateRecorderImpl(); // owned by this buffer; destroyed in dispose()
  }

  /** Clears the buffer and lets `save` write into it. */
  save(save: (recorder: JoltStateRecorder) => void): void {
    this.assertLive();
    this.recorder.Clear();
    save(this.recorder);
  }

  /**
   * Saves a whole world (SaveState with everything) after checking that the heap can take it: the buffer grows on
   * the WASM heap, and running out there would abort the module. Throws a clear Error instead.
   */
  saveWorld(world: PhysicsWorld): void {
    this.assertLive();
    world.ensureRoomForStateSave('FastStateBuffer.saveWorld');
    this.save((r) => world.system.SaveState(r, this.J.EStateRecorderState_All));
  }

  /** Restores what saveWorld saved into `world`; false if Jolt refused (its body set differs). */
  restoreWorld(world: PhysicsWorld): boolean {
    return this.restore((r) => world.system.RestoreState(r));
  }

  /** Rewinds and lets `restore` read from the start. */
  restore(restore: (recorder: JoltStateRecorder) => boolean | void): boolean {
    this.assertLive();
    this.recorder.Rewind();
    return restore(this.recorder) !== false;
  }

  /** Whether two buffers hold identical bytes. */
  isEqual(other: FastStateBuffer): boolean {
    return this.recorder.IsEqual(other.recorder);
  }

  private assertLive(): void {
    if (this.disposed) throw new Error('FastStateBuffer was disposed');
  }

  /** Frees the WASM-side buffer. */
  dispose(): void {
    if (this.disposed) return;
    this.disposed = true;
    this.J.destroy(this.recorder);
  }
}
