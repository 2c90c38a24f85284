// The OS scheduling priority of the calling thread (Linux: a thread id is a valid target of setpriority). A room worker
// whose rooms need more CPU than a tick period gives runs at the lowest priority, so it slows only itself: the main
// thread and the other workers get the cores first.
import { readlinkSync } from 'node:fs';
import { getPriority, setPriority } from 'node:os';

/** The niceness of a worker over its budget (the lowest priority). */
export const OVERLOADED_NICENESS = 19;

/** The calling thread's OS id, or null where the platform does not say (not Linux). */
export function currentThreadId(): number | null {
  try {
    const tid = Number(readlinkSync('/proc/thread-self').split('/').at(-1));
    return Number.isInteger(tid) && tid > 0 ? tid : null;
  } catch {
    return null;
  }
}

/**
 * Sets the calling thread's niceness; returns why it could not (no thread ids here, or no permission: an
 * unprivileged process may lower its priority but not raise it back), or null when done.
 */
export function setThreadNiceness(niceness: number): string | null {
  const tid = currentThreadId();
  if (tid === null) return 'this platform has no per-thread priorities';
  try {
    if (getPriority(tid) !== niceness) setPriority(tid, niceness);
    return null;
  } catch (error) {
    return error instanceof Error ? error.message : String(error);
  }
}
