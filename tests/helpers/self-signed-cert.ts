// A self-signed X.509 certificate for TLS tests, built with node:crypto alone (an ECDSA P-256 key, the DER written by
// hand): no openssl binary needed. The certificate names its hosts in subjectAltName, so clients that trust it as a
// CA accept it for those names and addresses.
import { generateKeyPairSync, randomBytes, sign, X509Certificate } from 'node:crypto';

function der(tag: number, body: Buffer): Buffer {
  const n = body.length;
  const len = n < 0x80 ? Buffer.from([n]) : n < 0x100 ? Buffer.from([0x81, n]) : Buffer.from([0x82, n >> 8, n & 0xff]);
  return Buffer.concat([Buffer.from([tag]), len, body]);
}
const seq = (...items: Buffer[]): Buffer => der(0x30, Buffer.concat(items));
const set = (...items: Buffer[]): Buffer => der(0x31, Buffer.concat(items));

function oid(dotted: string): Buffer {
  const parts = dotted.split('.').map(Number);
  const bytes = [40 * parts[0] + parts[1]];
  for (const p of parts.slice(2)) {
    const chunk = [p & 0x7f];
    for (let v = p >>> 7; v > 0; v >>>= 7) chunk.unshift((v & 0x7f) | 0x80);
    bytes.push(...chunk);
  }
  return der(0x06, Buffer.from(bytes));
}

function utcTime(d: Date): Buffer {
  const p = (n: number): string => String(n).padStart(2, '0');
  return der(0x17, Buffer.from(`${p(d.getUTCFullYear() % 100)}${p(d.getUTCMonth() + 1)}${p(d.getUTCDate())}${p(d.getUTCHours())}${p(d.getUTCMinutes())}${p(d.getUTCSeconds())}Z`, 'ascii'));
}

function ipBytes(ip: string): Buffer {
  if (ip.includes(':')) throw new Error('selfSignedCert: IPv6 addresses are not supported here');
  return Buffer.from(ip.split('.').map(Number));
}

/** A fresh self-signed certificate and its key (PEM) for `dnsNames` and `ipAddresses`, valid for a day. */
export function selfSignedCert(opts: { commonName?: string; dnsNames?: string[]; ipAddresses?: string[] } = {}): { cert: string; key: string } {
  const { privateKey, publicKey } = generateKeyPairSync('ec', { namedCurve: 'P-256' });
  const ecdsaSha256 = seq(oid('1.2.840.10045.4.3.2'));
  const name = seq(set(seq(oid('2.5.4.3'), der(0x0c, Buffer.from(opts.commonName ?? 'taos-physics test', 'utf8')))));
  const now = Date.now();
  const altNames = seq(
    ...(opts.dnsNames ?? ['localhost']).map((n) => der(0x82, Buffer.from(n, 'ascii'))),
    ...(opts.ipAddresses ?? ['127.0.0.1']).map((ip) => der(0x87, ipBytes(ip))),
  );
  const extensions = der(0xa3, seq(seq(oid('2.5.29.17'), der(0x04, altNames))));
  const serial = randomBytes(8);
  serial[0] &= 0x7f; // a positive INTEGER
  const tbs = seq(
    der(0xa0, der(0x02, Buffer.from([2]))), // v3
    der(0x02, serial),
    ecdsaSha256,
    name,
    seq(utcTime(new Date(now - 60_000)), utcTime(new Date(now + 86_400_000))),
    name,
    publicKey.export({ type: 'spki', format: 'der' }),
    extensions,
  );
  const signature = sign('sha256', tbs, privateKey); // DER-encoded ECDSA signature, as X.509 wants it
  const certDer = seq(tbs, ecdsaSha256, der(0x03, Buffer.concat([Buffer.from([0]), signature])));
  const cert = `-----BEGIN CERTIFICATE-----\n${certDer.toString('base64').replace(/.{64}/g, '$&\n').replace(/\n?$/, '\n')}-----END CERTIFICATE-----\n`;
  new X509Certificate(cert); // throws if the DER above is malformed
  return { cert, key: privateKey.export({ type: 'pkcs8', format: 'pem' }).toString() };
}
