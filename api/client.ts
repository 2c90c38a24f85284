// The `taos-physics/client` entry: the client library for browsers and Node (connect, clock sync, input sending,
// interpolation, transports). Loads no physics engine and no Node module.
export * from '../sdk/index.ts';
