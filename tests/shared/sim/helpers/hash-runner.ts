// Runs a fixed test-arena session with bots and reports the per-tick state hashes: as JSON on stdout when run as a
// child process, or posted to the parent when run as a worker thread. Used by the cross-process/thread tests.
import { isMainThread, parentPort, workerData } from 'node:worker_threads';
import { botRecords, makeSim, runHashes } from './sim-helpers.ts';

async function main(ticks: number): Promise<string[]> {
  const sim = await makeSim(undefined, { boxes: 12 }, 'cross-runtime');
  const hashes = runHashes(sim, botRecords(ticks, { bots: 3, leaveTicks: [-1, 70, -1] }));
  sim.destroy();
  return hashes;
}

if (isMainThread) {
  const ticks = Number(process.argv[2] ?? 120);
  const hashes = await main(ticks);
  process.stdout.write(JSON.stringify(hashes));
} else {
  parentPort!.postMessage(await main((workerData as { ticks: number }).ticks));
}
