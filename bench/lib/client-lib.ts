// The bench's one doorway into the client library: every figure, rig and helper process that acts as a real client
// imports it from here, so moving the library changes one path. It re-exports; it adds nothing.
export { AckCarrier, connect, InputLead, InputSender, webSocketTransport, ClockSync, type NetClient, type TransportFactory } from '../../sdk/index.ts';
