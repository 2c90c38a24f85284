// Tests for the serve command's connection and TLS flags: mistakes are usage errors (exit 2) found before anything
// starts.
import { describe, expect, it } from 'vitest';
import { portFromEnv } from '../../cli/serve-command.ts';
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

  it('takes its port from PORT when --port is not given, and refuses a bad PORT', async () => {
    expect(portFromEnv(undefined)).toBe(8080);
    expect(portFromEnv('')).toBe(8080);
    expect(portFromEnv('3000')).toBe(3000);
    expect(() => portFromEnv('http')).toThrow('PORT must be a TCP port (0-65535), got "http"');
    expect(() => portFromEnv('70000')).toThrow(/PORT must be a TCP port/);
    const saved = process.env.PORT;
    process.env.PORT = '-1';
    try {
      const r = await cli('serve');
      expect(r.code).toBe(2);
      expect(r.stderr).toMatch(/PORT must be a TCP port \(0-65535\), got "-1"/);
    } finally {
      if (saved === undefined) delete process.env.PORT;
      else process.env.PORT = saved;
    }
  });

  it('accepts json or pretty as --log-format', async () => {
    const r = await cli('serve', '--log-format', 'xml');
    expect(r.code).toBe(2);
    expect(r.stderr).toMatch(/--log-format must be json or pretty, got "xml"/);
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
