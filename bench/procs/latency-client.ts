// The input-latency figure's client process: one player on the client library (sdk/) over a real WebSocket.
// It toggles the Use button every interval, notes when the first input message carrying the new state leaves (a
// wrapped transport) and when a snapshot first shows it on its own character; prints the samples as one JSON line.
// Run: node bench/procs/latency-client.ts WS_URL TOGGLES INTERVAL_MS
import { connect, webSocketTransport, type TransportFactory } from '../lib/client-lib.ts';
import { ClientOpcode, unpackFrame } from '../../shared/protocol/index.ts';
import { Button, NEUTRAL_INPUT } from '../../shared/sim/input.ts';

const [url, togglesArg, intervalArg] = process.argv.slice(2);
const toggles = Number(togglesArg ?? 20);
const intervalMs = Number(intervalArg ?? 300);
if (!url || !Number.isInteger(toggles) || toggles < 1 || !(intervalMs > 0)) {
  process.stderr.write('usage: node bench/procs/latency-client.ts WS_URL TOGGLES INTERVAL_MS\n');
  process.exit(2);
}

interface Sample {
  /** performance.now() when the first input message with the new button state was handed to the socket. */
  sentMs: number;
  /** The tick that message stamped the new state for. */
  inputTick: number;
  /** The client's estimate of the server tick when it was sent. */
  serverTickAtSend: number;
  seenMs: number | null;
  seenTick: number | null;
}

let wanted = false;
let current: Sample | null = null;
const samples: Sample[] = [];
let estimate: () => number | null = () => null;

// Watches outgoing input messages for the first command that carries the wanted Use state.
const transport: TransportFactory = (target, handlers) => {
  const inner = webSocketTransport(target, handlers);
  return {
    send(data) {
      inner.send(data);
      if (current === null || current.sentMs >= 0) return;
      const msg = unpackFrame(data) as unknown[];
      if (msg[0] !== ClientOpcode.Input) return;
      const firstTick = msg[1] as number;
      const commands = msg[2] as number[][];
      for (let i = 0; i < commands.length; i++) {
        if (((commands[i][4] & Button.Use) !== 0) === wanted) {
          current.sentMs = performance.now();
          current.inputTick = firstTick + i;
          current.serverTickAtSend = estimate() ?? -1;
          return;
        }
      }
    },
    close: (code, reason) => inner.close(code, reason),
    bufferedAmount: () => inner.bufferedAmount(),
  };
};

const client = connect(url, { name: 'latency-probe', transport, reconnect: false });
estimate = () => client.serverTick();
client.on('snapshot', (s) => {
  if (current === null || current.sentMs < 0 || current.seenMs !== null) return;
  const me = s.view.characters.find((c) => c.playerId === client.playerId);
  if (me && ((me.buttons & Button.Use) !== 0) === wanted) {
    current.seenMs = performance.now();
    current.seenTick = s.tick;
  }
});
client.on('closed', (info) => {
  process.stderr.write(`latency-client: closed: ${info.reason}: ${info.detail}\n`);
});

await client.whenConnected();
// Let the clock sync settle (initial pings go out 100 ms apart).
await new Promise((r) => setTimeout(r, 1000));
for (let i = 0; i < toggles; i++) {
  wanted = !wanted;
  current = { sentMs: -1, inputTick: -1, serverTickAtSend: -1, seenMs: null, seenTick: null };
  client.setInput({ ...NEUTRAL_INPUT, buttons: wanted ? Button.Use : 0 });
  await new Promise((r) => setTimeout(r, intervalMs));
  samples.push(current);
}
const stats = client.stats();
process.stdout.write(`${JSON.stringify({ playerId: client.playerId, samples, leadTicks: stats.leadTicks, rttMs: stats.rttMs, missedInputTicks: stats.missedInputTicks })}\n`);
client.close();
setTimeout(() => process.exit(0), 200).unref();
