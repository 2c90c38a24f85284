// Describes an untrusted value for an error message without running any of its code: no String(x), no template
// literal on an object, no toString/valueOf/getter/Proxy trap is ever called. Never throws.

const MAX_STRING_CHARS = 40;
/** Bigints up to this magnitude are shown with their digits. */
const BIGINT_SHOWN = 1_000_000_000_000_000n;
// The built-in typed-array getters, called directly: they read internal slots, never the value's own properties,
// prototype chain or Proxy traps (as `instanceof` or `.byteLength` would).
const typedArrayPrototype = Object.getPrototypeOf(Uint8Array.prototype) as object;
const typedArrayName = Object.getOwnPropertyDescriptor(typedArrayPrototype, Symbol.toStringTag)!.get!;
const typedArrayByteLength = Object.getOwnPropertyDescriptor(typedArrayPrototype, 'byteLength')!.get!;

function describeNumber(n: number): string {
  if (Object.is(n, -0)) return '-0';
  return `${n}`; // a primitive: no user code runs
}

function describeString(s: string): string {
  const cut = s.length > MAX_STRING_CHARS ? `${s.slice(0, MAX_STRING_CHARS)}…` : s;
  // JSON escapes quotes, backslashes and control characters, so the text cannot break the message it sits in.
  return `${JSON.stringify(cut)}${s.length > MAX_STRING_CHARS ? ` (${s.length} characters)` : ''}`;
}

/**
 * A short, safe description of any value: numbers and booleans as written (−0, NaN and ±Infinity included),
 * strings quoted and cut, bigints with an `n`, and only the kind (and size) of anything else.
 */
export function describeValue(value: unknown): string {
  switch (typeof value) {
    case 'number':
      return describeNumber(value);
    case 'string':
      return describeString(value);
    case 'boolean':
      return value ? 'true' : 'false';
    case 'bigint':
      // A bigint's digits could be huge: say how big instead when they are.
      return value >= -BIGINT_SHOWN && value <= BIGINT_SHOWN ? `${value}n` : `a bigint of ${value < 0n ? '-' : ''}${(value < 0n ? -value : value).toString(16).length * 4} bits`;
    case 'undefined':
      return 'undefined';
    case 'symbol':
      return 'a symbol';
    case 'function':
      return 'a function';
    default:
      break;
  }
  if (value === null) return 'null';
  try {
    // Array.isArray and ArrayBuffer.isView run no code of the value either (a revoked Proxy throws).
    if (Array.isArray(value)) return 'an array';
    if (ArrayBuffer.isView(value)) return typedArrayName.call(value) === 'Uint8Array' ? `binary (${typedArrayByteLength.call(value) as number} bytes)` : 'a typed array';
  } catch {
    return 'an unreadable object';
  }
  return 'an object';
}
