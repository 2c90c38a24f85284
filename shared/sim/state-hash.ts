// The 64-bit state hash: two independent 32-bit multiply-rotate lanes (murmur3-style) over a stream of 32-bit words,
// cross-mixed at the end. Integer arithmetic only (Math.imul), so every engine gives the same 16 hex characters.

const C1 = 0xcc9e2d51;
const C2 = 0x1b873593;
const D1 = 0x85ebca77;
const D2 = 0xc2b2ae3d;

function fmix(h: number): number {
  h ^= h >>> 16;
  h = Math.imul(h, 0x85ebca6b);
  h ^= h >>> 13;
  h = Math.imul(h, 0xc2b2ae35);
  h ^= h >>> 16;
  return h >>> 0;
}

/** An incremental 64-bit hash of 32-bit words. */
export class Hasher64 {
  private a: number;
  private b: number;
  private count = 0;
  private readonly f64 = new Float64Array(1);
  private readonly f64Words = new Uint32Array(this.f64.buffer);
  private readonly f32 = new Float32Array(1);
  private readonly f32Word = new Uint32Array(this.f32.buffer);

  constructor(seed = 0) {
    this.a = 0;
    this.b = 0;
    this.reset(seed);
  }

  /** Starts over, as a new Hasher64(seed) would (reuse one hasher on hot paths: no allocation). */
  reset(seed = 0): this {
    this.a = (0x9e3779b9 ^ seed) >>> 0;
    this.b = (0x7f4a7c15 + seed) >>> 0;
    this.count = 0;
    return this;
  }

  /** Adds one 32-bit word (an integer; only its low 32 bits count). */
  word(w: number): this {
    let k = Math.imul(w, C1);
    k = (k << 15) | (k >>> 17);
    k = Math.imul(k, C2);
    let a = this.a ^ k;
    a = (a << 13) | (a >>> 19);
    this.a = (Math.imul(a, 5) + 0xe6546b64) | 0;
    let j = Math.imul(w ^ 0x5bd1e995, D1);
    j = (j << 17) | (j >>> 15);
    j = Math.imul(j, D2);
    let b = this.b ^ j;
    b = (b << 11) | (b >>> 21);
    this.b = (Math.imul(b, 9) + 0x52dce729) | 0;
    this.count++;
    return this;
  }

  /** Adds every word of an array view. */
  words(view: Uint32Array): this {
    let a = this.a;
    let b = this.b;
    for (let i = 0; i < view.length; i++) {
      const w = view[i];
      let k = Math.imul(w, C1);
      k = (k << 15) | (k >>> 17);
      k = Math.imul(k, C2);
      a ^= k;
      a = (a << 13) | (a >>> 19);
      a = (Math.imul(a, 5) + 0xe6546b64) | 0;
      let j = Math.imul(w ^ 0x5bd1e995, D1);
      j = (j << 17) | (j >>> 15);
      j = Math.imul(j, D2);
      b ^= j;
      b = (b << 11) | (b >>> 21);
      b = (Math.imul(b, 9) + 0x52dce729) | 0;
    }
    this.a = a;
    this.b = b;
    this.count += view.length;
    return this;
  }

  /** Adds a number's float64 bits (two words). */
  f64Bits(x: number): this {
    this.f64[0] = x;
    return this.word(this.f64Words[0]).word(this.f64Words[1]);
  }

  /** Adds a number rounded to float32, as its bits (one word). */
  f32Bits(x: number): this {
    this.f32[0] = x;
    return this.word(this.f32Word[0]);
  }

  /** Adds a string: its length, then its UTF-16 code units two per word. */
  string(s: string): this {
    this.word(s.length);
    for (let i = 0; i < s.length; i += 2) this.word(s.charCodeAt(i) | ((i + 1 < s.length ? s.charCodeAt(i + 1) : 0) << 16));
    return this;
  }

  /** The 64-bit digest as 16 lowercase hex characters (the hasher may keep going afterwards). */
  hex(): string {
    let a = (this.a ^ this.count) >>> 0;
    let b = (this.b ^ Math.imul(this.count, 0x9e3779b1)) >>> 0;
    a = (a + b) >>> 0;
    b = (b + a) >>> 0;
    a = fmix(a);
    b = fmix(b);
    a = (a + b) >>> 0;
    b = (b + a) >>> 0;
    return a.toString(16).padStart(8, '0') + b.toString(16).padStart(8, '0');
  }
}

/** The 64-bit hash of a list of 32-bit words, as 16 hex characters. */
export function hashWords(view: Uint32Array, seed = 0): string {
  return new Hasher64(seed).words(view).hex();
}
