// startServer's transport options on real sockets: HTTPS and WSS on one port with a self-signed certificate (the
// client library joins over wss:// trusting it), a clear start-up error for a bad certificate, and --trust-proxy
// honouring X-Forwarded-For only when set.
import { getCACertificates, setDefaultCACertificates } from 'node:tls';
import { afterAll, afterEach, beforeAll, describe, expect, it } from 'vitest';
import WebSocket from 'ws';
import { connect, type NetClient } from '../../sdk/client.ts';
import { silentLogger } from '../../server/logger.ts';
import { createMetrics } from '../../server/metrics.ts';
import { startServer, type RunningServer, type StartServerOptions } from '../../server/start-server.ts';
import { encodeClientMessage, PROTOCOL_VERSION } from '../../shared/protocol/index.ts';
import { selfSignedCert } from '../helpers/self-signed-cert.ts';
import { scenarioList } from './harness.ts';
import { stripScenario } from './test-scenarios.ts';

const tls = selfSignedCert({ dnsNames: ['localhost'], ipAddresses: ['127.0.0.1'] });
const systemCAs = getCACertificates('default');

let server: RunningServer | null = null;
const clients: NetClient[] = [];
beforeAll(() => {
  // Like a machine whose trust store holds a locally made CA: the platform WebSocket and fetch trust the certificate.
  setDefaultCACertificates([...systemCAs, tls.cert]);
});
afterAll(() => setDefaultCACertificates(systemCAs));
afterEach(async () => {
  for (const c of clients.splice(0)) c.close();
  await server?.close('test over');
  server = null;
});

function start(extra: Partial<StartServerOptions> = {}): Promise<RunningServer> {
  return startServer({
    port: 0,
    host: '127.0.0.1',
    scenario: 'test-strip',
    scenarios: scenarioList([stripScenario]),
    logger: silentLogger(),
    metrics: createMetrics({ processMetrics: false }),
    clientDir: '/nonexistent-client-dir',
    ...extra,
  });
}

async function waitFor(what: string, cond: () => boolean, timeoutMs = 5000): Promise<void> {
  const end = performance.now() + timeoutMs;
  while (!cond()) {
    if (performance.now() > end) throw new Error(`timed out after ${timeoutMs} ms waiting for ${what}`);
    await new Promise((r) => setTimeout(r, 10));
  }
}

describe('startServer with TLS', () => {
  it('serves HTTPS and WSS on one port: the client library joins over wss:// and gets snapshots', async () => {
    server = await start({ tls });
    expect(server.url).toMatch(/^https:\/\/127\.0\.0\.1:\d+\/$/);
    expect(server.wsUrl).toMatch(/^wss:\/\/127\.0\.0\.1:\d+\/$/);
    const health = await fetch(`${server.url}healthz`);
    expect(health.status).toBe(200);
    expect(await fetch(`https://localhost:${server.port}/api/rooms`).then((r) => r.status)).toBe(200);
    const client = connect(server.wsUrl, { name: 'Ada', reconnect: false });
    clients.push(client);
    const welcome = await client.whenConnected();
    expect(welcome.roomId).toBe('default');
    let snapshots = 0;
    client.on('snapshot', () => snapshots++);
    await waitFor('snapshots over wss', () => snapshots >= 3);
    // Nothing is served in the clear on that port.
    await expect(fetch(`http://127.0.0.1:${server.port}/healthz`)).rejects.toThrow();
  });

  it('refuses to start with a key that does not belong to the certificate, saying so', async () => {
    const other = selfSignedCert();
    await expect(start({ tls: { cert: tls.cert, key: other.key } })).rejects.toThrow(/cannot use the TLS certificate and key: .*key values mismatch/);
    await expect(start({ tls: { cert: 'not a certificate', key: tls.key } })).rejects.toThrow(/cannot use the TLS certificate and key/);
  });
});

describe('startServer --trust-proxy', () => {
  /** Opens a socket with forwarding headers and says hello; resolves once welcomed. */
  async function joinVia(url: string, headers: Record<string, string>): Promise<WebSocket> {
    const ws = new WebSocket(url, { headers });
    await new Promise<void>((resolve, reject) => {
      ws.once('open', () => resolve());
      ws.once('error', reject);
    });
    const welcomed = new Promise<void>((resolve) => ws.once('message', () => resolve()));
    ws.send(encodeClientMessage({ type: 'hello', version: PROTOCOL_VERSION, name: 'via-proxy', room: null }));
    await welcomed;
    return ws;
  }

  it('counts a client under its X-Forwarded-For address only when the proxy is trusted', async () => {
    const headers = { 'x-forwarded-for': '198.51.100.1, 203.0.113.9', 'x-forwarded-proto': 'https' };
    server = await start({ trustProxy: true });
    const trusted = await joinVia(server.wsUrl, headers);
    expect(server.policy.countsOf('203.0.113.9')).toEqual({ sockets: 1, pending: 0, kicks: 0 });
    expect(server.policy.countsOf('127.0.0.1').sockets).toBe(0);
    trusted.close();
    await server.close('next');
    server = await start();
    const ignored = await joinVia(server.wsUrl, headers);
    expect(server.policy.countsOf('203.0.113.9').sockets).toBe(0);
    expect(server.policy.countsOf('127.0.0.1').sockets).toBe(1);
    ignored.close();
  });
});
