// A local stand-in for the Agones SDK sidecar, for lifecycle tests without Kubernetes: a gRPC server on a loopback
// port built from the service definitions the npm SDK itself ships (agones.dev.sdk.SDK and .beta.SDK), keeping a
// GameServer's state, labels, counters and lists the way the sidecar reports them, and recording every call in order.
// It checks our use of the SDK's contract, not Agones itself.
import { createRequire } from 'node:module';
import * as grpc from '@grpc/grpc-js';

const require = createRequire(import.meta.url);
const sdkServices = require('@google-cloud/agones-sdk/lib/sdk_grpc_pb.js') as Record<string, grpc.ServiceDefinition>;
const sdkMessages = require('@google-cloud/agones-sdk/lib/sdk_pb.js') as any;
const betaServices = require('@google-cloud/agones-sdk/lib/beta/beta_grpc_pb.js') as Record<string, grpc.ServiceDefinition>;
const betaMessages = require('@google-cloud/agones-sdk/lib/beta/beta_pb.js') as any;

/** Kubernetes label values: at most 63 characters, alphanumeric at both ends, `-_.` inside. */
const LABEL_VALUE = /^(?:[A-Za-z0-9](?:[-_.A-Za-z0-9]{0,61}[A-Za-z0-9])?)?$/;

/** What the stand-in holds, as the sidecar would report it. */
export interface SidecarState {
  state: 'Scheduled' | 'Ready' | 'Allocated' | 'Shutdown';
  labels: Map<string, string>;
  counters: Map<string, { count: number; capacity: number }>;
  lists: Map<string, { capacity: number; values: string[] }>;
  healthPings: number;
}

/** A running stand-in sidecar. */
export interface AgonesSidecar {
  /** The port to put in AGONES_SDK_GRPC_PORT. */
  readonly port: number;
  readonly state: SidecarState;
  /** Every call in arrival order (`Ready`, `Health`, `SetLabel players=1`, `AddListValue rooms default`, …). */
  readonly calls: string[];
  /** Moves the GameServer to Allocated as an allocation from outside would (watchers are told). */
  allocateFromOutside(): void;
  stop(): Promise<void>;
}

type Unary = (call: grpc.ServerUnaryCall<any, any>, callback: grpc.sendUnaryData<any>) => void;

function fail(callback: grpc.sendUnaryData<any>, code: grpc.status, details: string): void {
  callback({ code, details, name: 'Error', message: details }, null);
}

/** Starts the stand-in; `declared` lists the counters and lists its GameServer spec declares (others are NOT_FOUND). */
export async function startAgonesSidecar(declared: { counters?: Record<string, number>; lists?: Record<string, number> } = {}): Promise<AgonesSidecar> {
  const state: SidecarState = {
    state: 'Scheduled',
    labels: new Map(),
    counters: new Map(Object.entries(declared.counters ?? {}).map(([k, capacity]) => [k, { count: 0, capacity }])),
    lists: new Map(Object.entries(declared.lists ?? {}).map(([k, capacity]) => [k, { capacity, values: [] }])),
    healthPings: 0,
  };
  const calls: string[] = [];
  const watchers = new Set<grpc.ServerWritableStream<any, any>>();

  const gameServer = (): any => {
    const gs = new sdkMessages.GameServer();
    const meta = new sdkMessages.GameServer.ObjectMeta();
    meta.setName('taos-physics-test');
    // Labels stay out: the SDK's generated code serializes maps with a jspb.Map method that google-protobuf 4 (its
    // own dependency) no longer has. Reading them works; the server reads only status.state anyway.
    gs.setObjectMeta(meta);
    const status = new sdkMessages.GameServer.Status();
    status.setState(state.state);
    status.setAddress('127.0.0.1');
    gs.setStatus(status);
    return gs;
  };
  const setState = (next: SidecarState['state']): void => {
    state.state = next;
    for (const w of watchers) w.write(gameServer());
  };
  const empty = (): any => new sdkMessages.Empty();
  const counterMessage = (name: string, c: { count: number; capacity: number }): any => {
    const m = new betaMessages.Counter();
    m.setName(name);
    m.setCount(c.count);
    m.setCapacity(c.capacity);
    return m;
  };
  const listMessage = (name: string, l: { capacity: number; values: string[] }): any => {
    const m = new betaMessages.List();
    m.setName(name);
    m.setCapacity(l.capacity);
    m.setValuesList([...l.values]);
    return m;
  };
  const lifecycle = (name: string, next: SidecarState['state']): Unary => (_call, callback) => {
    calls.push(name);
    setState(next);
    callback(null, empty());
  };

  const sdk: grpc.UntypedServiceImplementation = {
    ready: lifecycle('Ready', 'Ready'),
    allocate: lifecycle('Allocate', 'Allocated'),
    shutdown: lifecycle('Shutdown', 'Shutdown'),
    health: (call: grpc.ServerReadableStream<any, any>, callback: grpc.sendUnaryData<any>) => {
      call.on('data', () => {
        state.healthPings++;
        calls.push('Health');
      });
      call.on('end', () => callback(null, empty()));
      call.on('error', () => undefined);
    },
    getGameServer: ((_call, callback) => {
      calls.push('GetGameServer');
      callback(null, gameServer());
    }) as Unary,
    watchGameServer: (call: grpc.ServerWritableStream<any, any>) => {
      calls.push('WatchGameServer');
      watchers.add(call);
      call.on('cancelled', () => watchers.delete(call));
      call.on('close', () => watchers.delete(call));
    },
    setLabel: ((call, callback) => {
      const key = call.request.getKey() as string;
      const value = call.request.getValue() as string;
      if (!LABEL_VALUE.test(value)) return fail(callback, grpc.status.INVALID_ARGUMENT, `invalid label value ${JSON.stringify(value)}`);
      calls.push(`SetLabel ${key}=${value}`);
      state.labels.set(`agones.dev/sdk-${key}`, value);
      callback(null, empty());
    }) as Unary,
    setAnnotation: ((call, callback) => {
      calls.push(`SetAnnotation ${call.request.getKey() as string}`);
      callback(null, empty());
    }) as Unary,
    reserve: ((_call, callback) => {
      calls.push('Reserve');
      callback(null, empty());
    }) as Unary,
  };

  const beta: grpc.UntypedServiceImplementation = {
    getCounter: ((call, callback) => {
      const name = call.request.getName() as string;
      const c = state.counters.get(name);
      if (!c) return fail(callback, grpc.status.NOT_FOUND, `counter not found: ${name}`);
      callback(null, counterMessage(name, c));
    }) as Unary,
    updateCounter: ((call, callback) => {
      const u = call.request.getCounterupdaterequest();
      const name = u.getName() as string;
      const c = state.counters.get(name);
      if (!c) return fail(callback, grpc.status.NOT_FOUND, `counter not found: ${name}`);
      if (u.hasCapacity()) c.capacity = u.getCapacity().getValue() as number;
      if (u.hasCount()) {
        const count = u.getCount().getValue() as number;
        if (count < 0 || count > c.capacity) return fail(callback, grpc.status.OUT_OF_RANGE, `count ${count} out of range [0, ${c.capacity}]`);
        c.count = count;
      }
      if (u.getCountdiff() !== 0) c.count += u.getCountdiff() as number;
      calls.push(`UpdateCounter ${name} count=${c.count} capacity=${c.capacity}`);
      callback(null, counterMessage(name, c));
    }) as Unary,
    getList: ((call, callback) => {
      const name = call.request.getName() as string;
      const l = state.lists.get(name);
      if (!l) return fail(callback, grpc.status.NOT_FOUND, `list not found: ${name}`);
      callback(null, listMessage(name, l));
    }) as Unary,
    updateList: ((call, callback) => {
      const list = call.request.getList();
      const l = state.lists.get(list.getName() as string);
      if (!l) return fail(callback, grpc.status.NOT_FOUND, `list not found: ${list.getName() as string}`);
      l.capacity = list.getCapacity() as number;
      callback(null, listMessage(list.getName() as string, l));
    }) as Unary,
    addListValue: ((call, callback) => {
      const name = call.request.getName() as string;
      const value = call.request.getValue() as string;
      const l = state.lists.get(name);
      if (!l) return fail(callback, grpc.status.NOT_FOUND, `list not found: ${name}`);
      if (l.values.includes(value)) return fail(callback, grpc.status.ALREADY_EXISTS, `${value} already in ${name}`);
      if (l.values.length >= l.capacity) return fail(callback, grpc.status.OUT_OF_RANGE, `${name} is at capacity`);
      l.values.push(value);
      calls.push(`AddListValue ${name} ${value}`);
      callback(null, listMessage(name, l));
    }) as Unary,
    removeListValue: ((call, callback) => {
      const name = call.request.getName() as string;
      const value = call.request.getValue() as string;
      const l = state.lists.get(name);
      if (!l) return fail(callback, grpc.status.NOT_FOUND, `list not found: ${name}`);
      if (!l.values.includes(value)) return fail(callback, grpc.status.NOT_FOUND, `${value} not in ${name}`);
      l.values = l.values.filter((v) => v !== value);
      calls.push(`RemoveListValue ${name} ${value}`);
      callback(null, listMessage(name, l));
    }) as Unary,
  };

  const server = new grpc.Server();
  server.addService(sdkServices['agones.dev.sdk.SDK'], sdk);
  server.addService(betaServices['agones.dev.sdk.beta.SDK'], beta);
  const port = await new Promise<number>((resolve, reject) =>
    server.bindAsync('127.0.0.1:0', grpc.ServerCredentials.createInsecure(), (error, bound) => (error ? reject(error) : resolve(bound))),
  );
  return {
    port,
    state,
    calls,
    allocateFromOutside: () => setState('Allocated'),
    stop: () =>
      new Promise<void>((resolve) => {
        for (const w of watchers) w.end();
        server.tryShutdown(() => resolve());
        setTimeout(() => {
          server.forceShutdown();
          resolve();
        }, 2000).unref();
      }),
  };
}
