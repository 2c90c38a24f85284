// Headless Debian Firefox ESR for browser tests. Playwright cannot drive it, so a page under test reports by POSTing
// to the test's own loopback server; this only starts Firefox on a URL with a throw-away profile and stops it by PID.
import { spawn, type ChildProcess } from 'node:child_process';
import { existsSync } from 'node:fs';
import { mkdtemp, rm, writeFile } from 'node:fs/promises';
import { tmpdir } from 'node:os';
import { join } from 'node:path';
import { describe, it } from 'vitest';

/** Where Firefox ESR is looked for (override with FIREFOX_PATH). */
export const FIREFOX_PATH = process.env.FIREFOX_PATH ?? '/usr/bin/firefox-esr';

/** Why Firefox tests cannot run here, or null when they can. */
export function firefoxMissingReason(): string | null {
  if (!existsSync(FIREFOX_PATH)) return `Firefox ESR not found at ${FIREFOX_PATH} (install Debian's firefox-esr: apt-get install -y firefox-esr, or set FIREFOX_PATH)`;
  return null;
}

/** Preferences that keep a test profile quiet and off the network. */
const PREFS: Readonly<Record<string, boolean | number | string>> = {
  'browser.shell.checkDefaultBrowser': false,
  'browser.startup.homepage_override.mstone': 'ignore',
  'browser.aboutwelcome.enabled': false,
  'datareporting.policy.dataSubmissionEnabled': false,
  'datareporting.healthreport.uploadEnabled': false,
  'toolkit.telemetry.enabled': false,
  'app.update.disabledForTesting': true,
  'app.normandy.enabled': false,
  'extensions.update.enabled': false,
  'network.captive-portal-service.enabled': false,
  'network.connectivity-service.enabled': false,
  'browser.safebrowsing.malware.enabled': false,
  'browser.safebrowsing.phishing.enabled': false,
  'browser.newtabpage.enabled': false,
  'dom.disable_open_during_load': false,
};

/** A running headless Firefox; `output` collects its stderr (for failure messages). */
export interface FirefoxRun {
  readonly output: string[];
  /** Resolves when the process has exited. */
  readonly exited: Promise<number | null>;
  close(): Promise<void>;
}

/** Starts headless Firefox ESR on `url` with a fresh profile (deleted on close). */
export async function openInFirefox(url: string): Promise<FirefoxRun> {
  const profile = await mkdtemp(join(tmpdir(), 'taos-firefox-'));
  await writeFile(join(profile, 'user.js'), Object.entries(PREFS).map(([k, v]) => `user_pref(${JSON.stringify(k)}, ${JSON.stringify(v)});`).join('\n') + '\n');
  const child: ChildProcess = spawn(FIREFOX_PATH, ['--headless', '--no-remote', '--profile', profile, url], {
    stdio: ['ignore', 'ignore', 'pipe'],
    env: { ...process.env, MOZ_HEADLESS: '1' },
  });
  const output: string[] = [];
  child.stderr!.on('data', (d: Buffer) => {
    if (output.length < 200) output.push(d.toString('utf8'));
  });
  const exited = new Promise<number | null>((resolve) => {
    child.on('exit', (code) => resolve(code));
    child.on('error', (err) => {
      output.push(String(err));
      resolve(null);
    });
  });
  return {
    output,
    exited,
    async close() {
      if (child.exitCode === null && child.signalCode === null && child.pid !== undefined) {
        child.kill('SIGTERM');
        const killer = setTimeout(() => child.kill('SIGKILL'), 5000);
        await exited;
        clearTimeout(killer);
      }
      await rm(profile, { recursive: true, force: true });
    },
  };
}

/**
 * A describe block for Firefox tests: runs when Firefox ESR is present; without it, fails under CI=true and is
 * skipped with a clear message otherwise (as describeBrowser does for Chromium).
 */
export function describeFirefox(name: string, body: () => void): void {
  const missing = firefoxMissingReason();
  if (!missing) {
    describe(name, body);
    return;
  }
  if (process.env.CI === 'true') {
    describe(name, () => {
      it('needs Firefox', () => {
        throw new Error(`Firefox tests cannot run: ${missing}; CI=true, so this is a failure, not a skip`);
      });
    });
    return;
  }
  console.warn(`[browser tests skipped] ${name}: ${missing}`);
  describe.skip(name, body);
}
