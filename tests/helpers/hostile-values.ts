// Seeded hostile JavaScript values for validator property tests: objects whose toString/valueOf are numbers or throw,
// throwing getters, Proxies that throw on every trap, revoked Proxies, null prototypes, huge bigints, symbols,
// typed arrays, and every float edge. `touched` counts any code of a value that ran (a validator must run none in
// its error text; only reading a field may run a getter).
import type { Prng } from '../../shared/sim/prng.ts';
import { DANGEROUS_KEYS, EDGE_NUMBERS } from './hostile-frames.ts';

/** Counts how often a hostile value's own code ran. */
export const touched = { count: 0 };

const boom = (): never => {
  touched.count++;
  throw new Error('hostile code ran');
};

function trapEverything(): ProxyHandler<object> {
  return { get: boom, has: boom, ownKeys: boom, getOwnPropertyDescriptor: boom, getPrototypeOf: boom, set: boom, apply: boom, construct: boom, defineProperty: boom, deleteProperty: boom, isExtensible: boom, preventExtensions: boom, setPrototypeOf: boom };
}

/** An object with a field named by a dangerous key that holds a non-function (or a throwing function). */
function conversionBomb(rng: Prng): object {
  const o: Record<string, unknown> = {};
  for (const key of ['toString', 'valueOf']) {
    const r = rng.int(0, 2);
    o[key] = r === 0 ? 1 : r === 1 ? boom : { x: 1 };
  }
  if (rng.next() < 0.3) Object.setPrototypeOf(o, new Proxy({}, trapEverything()));
  if (rng.next() < 0.5) Object.defineProperty(o, Symbol.toPrimitive, { value: boom });
  return o;
}

/** One hostile value; containers recurse until `depth` runs out. */
export function hostileValue(rng: Prng, depth = 2): unknown {
  switch (rng.int(0, depth > 0 ? 15 : 11)) {
    case 0:
      return rng.pick(EDGE_NUMBERS);
    case 1:
      return rng.pick([0n, -1n, 2n ** 64n, -(2n ** 200n), 10n ** 400n]);
    case 2:
      return rng.pick(['', 'Ada', 'x'.repeat(5000), '\u0000\u202e', ...DANGEROUS_KEYS]);
    case 3:
      return rng.pick([null, undefined, true, false]);
    case 4:
      return rng.pick([Symbol('s'), Symbol.iterator]);
    case 5:
      return conversionBomb(rng);
    case 6: {
      const o = {};
      Object.defineProperty(o, rng.pick(['moveX', 'yaw', 'buttons', 'length', 'kind', 'x']), { get: boom, enumerable: true });
      return o;
    }
    case 7:
      return new Proxy({}, trapEverything());
    case 8: {
      const { proxy, revoke } = Proxy.revocable([], {});
      revoke();
      return proxy;
    }
    case 9:
      return rng.pick([new Uint8Array(3), new Float64Array([-0, Number.NaN]), new DataView(new ArrayBuffer(2)), new ArrayBuffer(4)]);
    case 10:
      return rng.pick([new Date(Number.NaN), /x/, () => 1, new Map([[1, 2]]), new Set([1]), new Error('e')]);
    case 11:
      return Object.create(null) as object;
    case 12:
      return Array.from({ length: rng.int(0, 6) }, () => hostileValue(rng, depth - 1));
    case 13: {
      const o: Record<string, unknown> = {};
      // Own properties, as a decoder would make them (assigning '__proto__' would set the prototype instead).
      for (let i = rng.int(0, 5); i > 0; i--) {
        Object.defineProperty(o, rng.pick(['moveX', 'moveZ', 'yaw', 'pitch', 'buttons', ...DANGEROUS_KEYS]), { value: hostileValue(rng, depth - 1), enumerable: true, writable: true, configurable: true });
      }
      return o;
    }
    case 14:
      return new Proxy([1, 2, 3, 4, 5], trapEverything());
    default: {
      // A command-shaped object with hostile fields: the shape validateInputCommand expects.
      const field = (): unknown => (rng.next() < 0.7 ? rng.pick(EDGE_NUMBERS) : rng.next() < 0.5 ? rng.range(-300, 300) : hostileValue(rng, depth - 1));
      return { moveX: field(), moveZ: field(), yaw: field(), pitch: field(), buttons: field() };
    }
  }
}
