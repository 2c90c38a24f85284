// Plain vectors and quaternions: the value types physics, simulation, protocol and renderer exchange. Copies, never
// handles into the WASM heap.

/** A plain 3-vector (metres, metres per second, …: the name of the field that holds it says which). */
export interface Vec3Like {
  x: number;
  y: number;
  z: number;
}

/** A plain unit quaternion. */
export interface QuatLike {
  x: number;
  y: number;
  z: number;
  w: number;
}

/** The rotation that leaves everything as it is. */
export const IDENTITY_QUAT: QuatLike = Object.freeze({ x: 0, y: 0, z: 0, w: 1 });
