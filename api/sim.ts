// The `taos-physics/sim` entry: run a scenario in code (Simulation, scripted bots), write and read input logs, and
// replay a log with its hash checks. Node (input logs are files; Jolt loads from the package).
import '../server/physics-node.ts';
export { Simulation, type SimulationOptions } from '../shared/sim/simulation.ts';
export { BotScript, type BotScriptOptions } from '../shared/sim/bots.ts';
export { emptyTickInput, type BodyDescriptor, type PlayerJoin } from '../shared/sim/types.ts';
export { NEUTRAL_INPUT, quantizeInput } from '../shared/sim/input.ts';
export { resolveParams } from '../shared/sim/scenario.ts';
export { SessionLog, type SessionLogOptions } from '../server/log/session-log.ts';
export { LogReader, LogWriter, readLogBytes, LogCorruptError, LogFormatError, LOG_FORMAT_VERSION, type LogEntry, type LogHeader, type LogOutcome, type LogStatus } from '../server/log/index.ts';
export { scenarioModuleHash } from '../server/scenario-module.ts';
export { replayLog, ScenarioVersionError, type ReplayDivergence, type ReplayOptions, type ReplayReport } from '../cli/replay-session.ts';
export * from './scenario-kit.ts';
