// Tests for the serve command's connection and TLS flags: mistakes are usage errors (exit 2) found before anything
// starts.
import { describe, expect, it } from 'vitest';
import { cli } from '../helpers/cli.ts';

describe('serve command', () => {
  it('wants --tls-cert and --tls-key together, and readable', async () => {
    const alone = await cli('serve', '--tls-cert', 'cert.pem');
    expect(alone.code).toBe(2);
    expect(alone.stderr).toMatch(/--tls-cert and --tls-key go together/);
    const missing = await cli('serve', '--tls-cert', '/nonexistent/cert.pem', '--tls-key', '/nonexistent/key.pem');
    expect(missing.code).toBe(2);
    expect(missing.stderr).toMatch(/cannot read --tls-cert \/nonexistent\/cert\.pem: ENOENT/);
  });

  it('checks the connection limits', async () => {
    const r = await cli('serve', '--max-connections-per-address', '0');
    expect(r.code).toBe(2);
    expect(r.stderr).toMatch(/--max-connections-per-address must be ≥ 1, got 0/);
    expect((await cli('serve', '--hello-timeout-ms', '5s')).stderr).toMatch(/--hello-timeout-ms must be an integer/);
    expect((await cli('serve', '--trust-proxy=yes')).stderr).toMatch(/--trust-proxy takes no value/);
  });

  it('checks the durability and checkpoint flags', async () => {
    const bad = await cli('serve', '--durability', 'sometimes');
    expect(bad.code).toBe(2);
    expect(bad.stderr).toMatch(/--durability must be one of tick, interval, off, got "sometimes"/);
    expect((await cli('serve', '--durability-interval-ms', '100')).stderr).toMatch(/--durability-interval-ms goes with --durability interval/);
    expect((await cli('serve', '--checkpoint-every', '-1')).code).toBe(2);
    expect((await cli('serve', '--help')).stdout).toMatch(/--durability MODE/);
  });
});
