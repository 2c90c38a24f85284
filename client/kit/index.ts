// The browser kit served at /kit.js: the client library plus play() (the stock renderer driven by a connection),
// for pages a game writes itself (`import { play } from '/kit.js'`).
export * from '../../sdk/index.ts';
export { play, type PlayHandle, type PlayOptions } from './play.ts';
export { Renderer } from '../render/renderer.ts';
