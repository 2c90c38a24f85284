// Worker-thread body of `verify --workers`: replays the log named in workerData in this thread's own Jolt heap and
// posts the ReplayReport (with every per-tick hash) back, or the error message.
import { parentPort, workerData } from 'node:worker_threads';
import { replayLog } from './replay-session.ts';
import { scenarioFromArg } from './scenario-setup.ts';

const { file, scenarioPath, force } = workerData as { file: string; scenarioPath?: string; force: boolean };
try {
  const scenario = scenarioPath === undefined ? undefined : await scenarioFromArg(scenarioPath);
  const report = await replayLog(file, { collectHashes: true, force, ...(scenario !== undefined ? { scenario } : {}) });
  parentPort!.postMessage({ ok: true, report });
} catch (err) {
  parentPort!.postMessage({ ok: false, error: (err as Error).message });
}
