// Bytes on the wire: WebSocket frame sizes (RFC 6455 header lengths; server→client frames are unmasked, client→server
// frames carry a 4-byte mask) and bits-per-second arithmetic for the bandwidth figures.

/** Size of a server→client binary frame carrying `payloadBytes` (2-byte header up to 125 B, 4 up to 64 KiB, else 10). */
export function wsFrameBytes(payloadBytes: number): number {
  if (!Number.isInteger(payloadBytes) || payloadBytes < 0) throw new Error(`wsFrameBytes: payload must be a byte count, got ${payloadBytes}`);
  const header = payloadBytes <= 125 ? 2 : payloadBytes <= 65535 ? 4 : 10;
  return header + payloadBytes;
}

/** Size of a client→server frame (the header plus the 4-byte masking key). */
export function wsClientFrameBytes(payloadBytes: number): number {
  return wsFrameBytes(payloadBytes) + 4;
}

/** Kilobits per second (1 kbit = 1000 bits) of `bytes` spread over `seconds`. */
export function kbps(bytes: number, seconds: number): number {
  if (!(seconds > 0)) throw new Error(`kbps: seconds must be > 0, got ${seconds}`);
  return (bytes * 8) / 1000 / seconds;
}
