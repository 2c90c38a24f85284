// Server-to-client WebSocket framing (RFC 6455 §5.2) for the gateway's one write per socket per turn: each message
// becomes a final, unmasked binary frame, all of them laid out in one buffer. Only what a server sends: no masking,
// no fragments, no compression (the gateway turns permessage-deflate off).

/** Bytes of the frame header (opcode byte plus length) in front of a `payloadBytes` message. */
export function frameHeaderBytes(payloadBytes: number): number {
  return payloadBytes < 126 ? 2 : payloadBytes < 65536 ? 4 : 10;
}

/** The messages as consecutive binary frames in one buffer (`totalBytes`: their payload bytes plus every header). */
export function frameBinaryMessages(messages: readonly Uint8Array[], totalBytes: number): Buffer {
  const out = Buffer.allocUnsafe(totalBytes);
  let at = 0;
  for (const m of messages) {
    const n = m.length;
    out[at] = 0x82; // FIN + binary
    if (n < 126) {
      out[at + 1] = n;
      at += 2;
    } else if (n < 65536) {
      out[at + 1] = 126;
      out.writeUInt16BE(n, at + 2);
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
  return out;
}
