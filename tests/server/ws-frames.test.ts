// Tests of the server's WebSocket framing: the frames are byte for byte what `ws` itself sends for the same binary
// messages (every length form), a ws client reads them back as the messages, in order, and the reused scratch never
// overwrites frames handed off to a queued write.
import { EventEmitter } from 'node:events';
import * as wsModule from 'ws';
import { describe, expect, it } from 'vitest';
import { frameBinaryMessages, frameHeaderBytes, FrameWriter } from '../../server/ws-frames.ts';

// ws exports its sender and receiver, but its type package does not declare them.
const { Receiver, Sender } = wsModule as unknown as {
  Receiver: new (o: { isServer: boolean }) => EventEmitter & { write(chunk: Buffer): void };
  Sender: { frame(data: Buffer, o: object): Buffer[] };
};

/** What ws's own sender writes for one binary message from a server (unmasked, final frame, no compression). */
function wsFrame(payload: Uint8Array): Buffer {
  const parts = Sender.frame(Buffer.from(payload), { fin: true, opcode: 2, mask: false, rsv1: false, readOnly: false });
  return Buffer.concat(parts);
}

const message = (n: number, seed: number): Uint8Array => Uint8Array.from({ length: n }, (_, i) => (i * 31 + seed) & 0xff);

describe('ws-frames', () => {
  it('frames messages as ws does, at every length form (7-bit, 16-bit, 64-bit)', () => {
    const sizes = [0, 1, 125, 126, 127, 65535, 65536, 70_000];
    const messages = sizes.map((n, i) => message(n, i));
    const total = messages.reduce((sum, m) => sum + frameHeaderBytes(m.length) + m.length, 0);
    expect(frameBinaryMessages(messages, total)).toEqual(Buffer.concat(messages.map(wsFrame)));
  });

  it('gives a ws receiver the messages back, in order', () => {
    const messages = [message(3, 1), message(300, 2), message(90, 3)];
    const total = messages.reduce((sum, m) => sum + frameHeaderBytes(m.length) + m.length, 0);
    const received: Buffer[] = [];
    const receiver = new Receiver({ isServer: false });
    receiver.on('message', (data: Buffer, isBinary: boolean) => {
      expect(isBinary).toBe(true);
      received.push(data);
    });
    receiver.write(frameBinaryMessages(messages, total));
    expect(received.map((b) => [...b])).toEqual(messages.map((m) => [...m]));
  });

  it('frames into its scratch the same bytes, and leaves frames it handed off untouched by later ones', () => {
    const writer = new FrameWriter();
    const a = [message(200, 1), message(3, 2)];
    const b = [message(90, 3)];
    const bytes = (ms: Uint8Array[]): number => ms.reduce((sum, m) => sum + frameHeaderBytes(m.length) + m.length, 0);
    const first = writer.frame(a, bytes(a));
    const copy = Buffer.from(first);
    expect(first).toEqual(frameBinaryMessages(a, bytes(a)));
    writer.handOff();
    expect(writer.frame(b, bytes(b))).toEqual(frameBinaryMessages(b, bytes(b)));
    expect(first).toEqual(copy);
    // Larger than the scratch: a buffer of its own.
    const big = [message(40_000, 4)];
    expect(writer.frame(big, bytes(big))).toEqual(frameBinaryMessages(big, bytes(big)));
  });

  it('refuses a total that does not match the frames', () => {
    expect(() => frameBinaryMessages([message(5, 0)], 8)).toThrow(/take 7 bytes, not the 8 given/);
  });
});
