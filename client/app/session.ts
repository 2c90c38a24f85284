// Interim: the page's network session will be an adapter over the client library (client/net), which is still being
// written; until it lands, joining reports that clearly instead of pretending to connect.
import type { NetSession, SessionHandlers } from './session-types.ts';

/** Opens a session to the room (interim: always reports that networking is not built yet). */
export function openSession(_url: string, _opts: { name: string; room: string | null }, handlers: SessionHandlers): NetSession {
  queueMicrotask(() => handlers.onClosed('unavailable', 'This build has no network client yet (client/net is not in the tree).'));
  return {
    serverTick: 0,
    rttMs: null,
    frame: () => ({ view: null, renderTick: 0, bufferDepth: 0, delayMs: 0 }),
    setInput: () => undefined,
    close: () => undefined,
  };
}
