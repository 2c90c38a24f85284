// A room worker thread's entry point: loads Jolt and the scenarios, then runs the rooms the main thread opens in it
// (server/workers/worker-rooms.ts) until the main thread ends it. Started by RoomThread, never run directly.
import '../physics-node.ts';
import { parentPort, workerData } from 'node:worker_threads';
import { SystemClock } from '../clock.ts';
import { pino } from 'pino';
import { createMetrics } from '../metrics.ts';
import { createRoomFactory } from '../room-factory.ts';
import type { ToWorker, WorkerInit } from './worker-protocol.ts';
import { WorkerRooms } from './worker-rooms.ts';
import { loadScenarioSource } from './worker-scenarios.ts';

const port = parentPort;
if (!port) throw new Error('server/workers/room-worker.ts runs only as a worker thread');
const init = workerData as WorkerInit;
// Log lines go to the main thread, whose logger writes them where the server's own lines go.
const logger = pino({ level: init.logLevel, base: { worker: init.index } }, { write: (line: string) => port.postMessage({ t: 'log', line }) });
const scenarios = await loadScenarioSource(init.scenarioModules);
const rooms = new WorkerRooms({
  factory: createRoomFactory({ scenarios, logger, recordDir: init.config.recordDir, hashEveryTicks: init.config.recordHashEveryTicks, durability: init.config.durability, checkpointEverySeconds: init.config.checkpointEverySeconds }),
  clock: new SystemClock(),
  metrics: createMetrics({ processMetrics: false }),
  logger,
  config: init.config,
  post: (msg, transfer) => port.postMessage(msg, transfer ?? []),
  worker: { index: init.index, count: init.count },
});
port.on('message', (msg: ToWorker) => rooms.handle(msg));
port.postMessage({ t: 'ready' });
