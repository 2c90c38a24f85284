// Browser side of the cross-runtime determinism check (bundled by host.ts): runs every scenario's golden script and
// resumes Node-made checkpoints through this browser's copy of the Simulation, then POSTs the raw hashes back.
// It judges nothing itself; the Node test compares. Runs unchanged in Chromium and Firefox (no Playwright needed).
import { listScenarios, getScenario } from '../../../scenarios/index.ts';
import { setDefaultPhysicsInitOptions } from '../../../shared/physics/index.ts';
import { runGolden } from '../../../shared/sim/golden.ts';
import { Simulation } from '../../../shared/sim/simulation.ts';
import type { SimCheckJob, SimCheckResult, ResumeResult } from './protocol.ts';

function fromBase64(b64: string): Uint8Array {
  return Uint8Array.from(atob(b64), (c) => c.charCodeAt(0));
}

async function resume(job: SimCheckJob['resumes'][number]): Promise<ResumeResult> {
  const sim = await Simulation.create({ scenario: getScenario(job.scenario), seed: job.seed });
  try {
    sim.restoreCheckpointBytes(fromBase64(job.checkpointB64));
    const restoredTick = sim.tick;
    const hashes: string[] = [];
    let fast = null;
    let fastIndex = -1;
    for (let i = 0; i < job.records.length; i++) {
      if (i === job.fastCheckpointAfter) {
        fast = sim.saveCheckpoint();
        fastIndex = i;
      }
      sim.step(job.records[i]);
      hashes.push(sim.stateHash());
    }
    // Roll back to the fast checkpoint and play the same records again: the hashes must repeat.
    const rerunHashes: string[] = [];
    if (fast) {
      sim.restoreCheckpoint(fast);
      fast.dispose();
      for (let i = fastIndex; i < job.records.length; i++) {
        sim.step(job.records[i]);
        rerunHashes.push(sim.stateHash());
      }
    }
    return { scenario: job.scenario, restoredTick, hashes, rerunFrom: fastIndex, rerunHashes };
  } finally {
    sim.destroy();
  }
}

async function run(): Promise<SimCheckResult> {
  const job = (await (await fetch('job.json')).json()) as SimCheckJob;
  setDefaultPhysicsInitOptions({ wasmUrl: new URL(job.wasmFile, location.href).href });
  const goldens: SimCheckResult['goldens'] = [];
  for (const def of listScenarios()) {
    const r = await runGolden(def);
    goldens.push({ scenario: r.scenario, ticks: r.ticks, hash: r.hash, checkpoints: r.checkpoints });
  }
  const resumes: ResumeResult[] = [];
  for (const r of job.resumes) resumes.push(await resume(r));
  return { userAgent: navigator.userAgent, goldens, resumes, error: null };
}

async function report(result: SimCheckResult): Promise<void> {
  await fetch('result', { method: 'POST', headers: { 'content-type': 'application/json' }, body: JSON.stringify(result) });
  document.title = 'sim-check done';
}

run().then(report, (err: unknown) => {
  const e = err as Error;
  return report({ userAgent: navigator.userAgent, goldens: [], resumes: [], error: `${e.message}\n${e.stack ?? ''}` });
});
