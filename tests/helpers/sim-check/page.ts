// Browser side of the cross-runtime determinism check (bundled by host.ts beside a production client build): loads
// the shipped physics chunk (the page's own Simulation, as /replay loads it), runs every scenario's golden script and
// resumes Node-made checkpoints, then POSTs the raw hashes back. It judges nothing; the Node test compares. Runs
// unchanged in Chromium and Firefox (no Playwright needed).
import type { Physics } from '../../../client/app/physics-loader.ts';
import { BotScript } from '../../../shared/sim/bots.ts';
import type { ResumeResult, SimCheckJob, SimCheckResult } from './protocol.ts';

function fromBase64(b64: string): Uint8Array {
  return Uint8Array.from(atob(b64), (c) => c.charCodeAt(0));
}

/** The golden run of shared/sim/golden.ts (runGolden, whose constants the job carries), on the chunk's Simulation. */
async function golden(physics: Physics, rules: SimCheckJob['golden'], name: string): Promise<SimCheckResult['goldens'][number]> {
  const def = physics.getScenario(name);
  const sim = await physics.Simulation.create({ scenario: def, seed: rules.seed });
  try {
    const script = new BotScript({ seed: rules.seed, bots: def.golden.bots, joinSpacingTicks: rules.joinSpacingTicks });
    const checkpoints: Array<{ tick: number; hash: string }> = [];
    for (let t = 0; t < def.golden.ticks; t++) {
      sim.step(script.next());
      if (sim.tick % rules.hashEveryTicks === 0) checkpoints.push({ tick: sim.tick, hash: sim.stateHash() });
    }
    return { scenario: name, ticks: def.golden.ticks, hash: sim.stateHash(), checkpoints };
  } finally {
    sim.destroy();
  }
}

async function resume(physics: Physics, job: SimCheckJob['resumes'][number]): Promise<ResumeResult> {
  const sim = await physics.Simulation.create({ scenario: physics.getScenario(job.scenario), seed: job.seed });
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
  // A runtime URL: the production chunk is loaded as built, not bundled into this page.
  const physics = (await import(new URL(job.physicsChunk, location.href).href)) as Physics;
  await physics.startPhysics();
  const goldens: SimCheckResult['goldens'] = [];
  for (const def of physics.listScenarios()) goldens.push(await golden(physics, job.golden, def.name));
  const resumes: ResumeResult[] = [];
  for (const r of job.resumes) resumes.push(await resume(physics, r));
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
