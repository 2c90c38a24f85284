// Server-to-client WebSocket framing (RFC 6455 §5.2) for the gateway's one write per socket per turn: each message
// becomes a final, unmasked binary frame, all of them laid out in one buffer. Only what a server sends: no masking,
// no fragments, no compression (the gateway turns permessage-deflate off).

/** Bytes of the frame header (opcode byte plus length) in front of a `payloadBytes` message. */
export function frameHeaderBytes(payloadBytes: number): number {
  return payloadBytes < 126 ? 2 : payloadBytes < 65536 ? 4 : 10;
}

/** Writes the messages as consecutive binary frames into `out` (exactly `totalBytes` long). */
function writeFrames(out: Buffer, messages: readonly Uint8Array[], totalBytes: number): void {
  let at = 0;
  for (let i = 0; i < messages.length; i++) {
    const m = messages[i];
    const n = m.length;
    out[at] = 0x82; // FIN + binary
    if (n < 126) {
      out[at + 1] = n;
      at += 2;
    } else if (n < 65536) {
      out[at + 1] = 126;
      out[at + 2] = n >>> 8;
      out[at + 3] = n & 0xff;
      at += 4;
    } else {
      out[at + 1] = 127;
      out.writeUInt16BE(0, at + 2);
      out.writeUIntBE(n, at + 4, 6);
      at += 10;
    }
    out.set(m, at);
    at += n;
  }
  if (at !== totalBytes) throw new Error(`frameBinaryMessages: the frames take ${at} bytes, not the ${totalBytes} given`);
}

/** The messages as consecutive binary frames in a new buffer (`totalBytes`: their payload bytes plus every header). */
export function frameBinaryMessages(messages: readonly Uint8Array[], totalBytes: number): Buffer {
  const out = Buffer.allocUnsafe(totalBytes);
  writeFrames(out, messages, totalBytes);
  return out;
}

/**
 * Frames into one reused scratch buffer instead of a new one per write. A socket write that completes at once
 * (the usual case: the kernel takes the bytes) leaves nothing referring to it; when a write is queued instead, the
 * caller says so with handOff() and the stream keeps that buffer: the next frames go into a fresh one.
 */
export class FrameWriter {
  private scratch: Buffer = Buffer.allocUnsafeSlow(16 * 1024);

  /** The frames of `messages` (`totalBytes` long, headers included): valid until the next frame() call. */
  frame(messages: readonly Uint8Array[], totalBytes: number): Buffer {
    if (totalBytes > this.scratch.length) return frameBinaryMessages(messages, totalBytes);
    const out = this.scratch.subarray(0, totalBytes);
    writeFrames(out, messages, totalBytes);
    return out;
  }

  /** The last frames went to a write that was queued: their memory now belongs to that write. */
  handOff(): void {
    this.scratch = Buffer.allocUnsafeSlow(this.scratch.length);
  }
}
