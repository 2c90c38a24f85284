// Browser test of issue 13 item 4: a recording server process under a connected page is killed with SIGKILL and
// restarted with --resume on the same port; the page says "Server restarted, rejoining", then plays on as the same
// player in the same room without a reload (the default scenario: a page that predicted comes back to a resumed room,
// which serves snapshots).
import { spawn, type ChildProcess } from 'node:child_process';
import { mkdtempSync, rmSync } from 'node:fs';
import { tmpdir } from 'node:os';
import { join } from 'node:path';
import { afterAll, beforeAll, expect, it } from 'vitest';
import type { TaosState } from '../../client/app/test-hook.ts';
import { buildClient } from '../../scripts/build-client.ts';
import { describeBrowser, launchBrowser, readHook, waitForHook, type BrowserSession } from '../helpers/browser.ts';

const root = new URL('../../', import.meta.url).pathname;
const tmp = mkdtempSync(join(tmpdir(), 'taos-restart-page-'));

/** A `serve` process; resolves once it printed its URL. */
async function serve(args: string[]): Promise<{ child: ChildProcess; url: string; exited: Promise<void> }> {
  const child = spawn(join(root, 'node_modules/.bin/node'), [join(root, 'bin/taos-physics.js'), 'serve', '--log-level', 'warn', ...args], { cwd: root, stdio: ['ignore', 'pipe', 'pipe'], env: { ...process.env, VITEST: '' } });
  const exited = new Promise<void>((resolve) => child.on('exit', () => resolve()));
  let out = '';
  let err = '';
  child.stderr!.on('data', (d: Buffer) => (err += d.toString()));
  const url = await new Promise<string>((resolve, reject) => {
    const timer = setTimeout(() => reject(new Error(`serve printed no URL in 30 s: ${err}`)), 30_000);
    child.stdout!.on('data', (d: Buffer) => {
      out += d.toString();
      const m = /(http:\/\/\S+\/)/.exec(out);
      if (m) {
        clearTimeout(timer);
        resolve(m[1]);
      }
    });
  });
  return { child, url, exited };
}

describeBrowser('server restart under a connected page', () => {
  let browser: BrowserSession;
  let clientDir: string;

  beforeAll(async () => {
    clientDir = (await buildClient()).outDir;
    browser = await launchBrowser();
  });

  afterAll(async () => {
    await browser?.close();
    rmSync(tmp, { recursive: true, force: true });
  });

  it('says the server restarted and rejoins as the same player after kill -9 and serve --resume', async () => {
    const dir = join(tmp, 'rec');
    const common = ['--client-dir', clientDir];
    const first = await serve(['--port', '0', '--record', dir, ...common]);
    let second: Awaited<ReturnType<typeof serve>> | null = null;
    try {
      const { page } = await browser.newPage();
      await page.goto(new URL('/?room=default', first.url).href);
      await waitForHook(page, 't.connected && t.framesRendered >= 2');
      const before = await readHook<TaosState>(page);
      const titles: string[] = [];
      await page.exposeFunction('__sawTitle', (text: string) => titles.push(text));
      await page.evaluate(() => {
        const box = document.getElementById('message')!;
        new MutationObserver(() => (window as unknown as { __sawTitle(t: string): void }).__sawTitle(box.querySelector('h2')?.textContent ?? '')).observe(box, { childList: true, subtree: true, characterData: true });
      });
      first.child.kill('SIGKILL');
      await first.exited;
      second = await serve(['--port', new URL(first.url).port, '--resume', dir, ...common]);
      await waitForHook(page, `t.connected && t.serverTick > ${before.serverTick + 30}`, 60_000);
      expect(titles).toContain('Server restarted, rejoining');
      const after = await readHook<TaosState>(page);
      expect(after).toMatchObject({ page: 'playing', playerId: before.playerId, roomId: before.roomId });
      await page.close();
    } finally {
      first.child.kill('SIGKILL');
      second?.child.kill('SIGKILL');
    }
  }, 120_000);
});
