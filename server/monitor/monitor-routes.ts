// HTTP routes of the monitor: GET /monitor (the page), GET /monitor/state (JSON), GET /monitor/events (Server-Sent
// Events: one `state` event per sample), POST /monitor/rooms/ID/close and POST /monitor/rooms/ID/players/N/kick.
// Who may call them is access control's business (server/access/http-guard.ts: everything under /monitor/ needs the
// admin token when one is set); the page itself holds no data and stays open.
import type { IncomingMessage, ServerResponse } from 'node:http';
import { HttpError, HttpErrorCode, sendJson } from '../http-errors.ts';
import { MONITOR_PAGE_HTML } from './monitor-page.ts';
import type { ServerMonitor } from './server-monitor.ts';

/** Answers a /monitor request; resolves false when the path is not one of its routes. */
export type MonitorRoutes = (req: IncomingMessage, res: ServerResponse, method: string, path: string) => Promise<boolean>;

function allow(method: string, path: string, allowed: string): void {
  if (!allowed.split(', ').includes(method)) throw new HttpError(405, HttpErrorCode.MethodNotAllowed, `${method} ${path} is not supported (allowed: ${allowed})`, { allow: allowed });
}

function segment(text: string): string {
  try {
    return decodeURIComponent(text);
  } catch {
    throw new HttpError(400, HttpErrorCode.BadUrl, `malformed percent-encoding in ${JSON.stringify(text.slice(0, 80))}`);
  }
}

/** The monitor's routes over a ServerMonitor. */
export function createMonitorRoutes(monitor: ServerMonitor): MonitorRoutes {
  return async (req, res, method, path) => {
    if (path === '/monitor' || path === '/monitor/') {
      allow(method, path, 'GET, HEAD');
      res.writeHead(200, {
        'content-type': 'text/html; charset=utf-8',
        'cache-control': 'no-store',
        'content-security-policy': "default-src 'none'; img-src data:; script-src 'unsafe-inline'; style-src 'unsafe-inline'; connect-src 'self'",
        'x-content-type-options': 'nosniff',
      });
      res.end(method === 'HEAD' ? undefined : MONITOR_PAGE_HTML);
      return true;
    }
    if (path === '/monitor/state') {
      allow(method, path, 'GET, HEAD');
      sendJson(res, 200, monitor.state());
      return true;
    }
    if (path === '/monitor/events') {
      allow(method, path, 'GET');
      res.writeHead(200, { 'content-type': 'text/event-stream; charset=utf-8', 'cache-control': 'no-store', connection: 'keep-alive', 'x-accel-buffering': 'no' });
      res.flushHeaders();
      const unsubscribe = monitor.subscribe((state) => {
        res.write(`event: state\ndata: ${JSON.stringify(state)}\n\n`);
      });
      res.on('close', unsubscribe);
      req.on('close', unsubscribe);
      return true;
    }
    const close = /^\/monitor\/rooms\/([^/]+)\/close$/.exec(path);
    if (close) {
      allow(method, path, 'POST');
      req.resume();
      const id = segment(close[1]);
      await monitor.closeRoom(id);
      sendJson(res, 200, { closed: id });
      return true;
    }
    const kick = /^\/monitor\/rooms\/([^/]+)\/players\/([^/]+)\/kick$/.exec(path);
    if (kick) {
      allow(method, path, 'POST');
      req.resume();
      const id = segment(kick[1]);
      const playerText = segment(kick[2]);
      if (!/^[1-9]\d{0,8}$/.test(playerText)) throw new HttpError(400, HttpErrorCode.BadUrl, `player id must be a positive integer, got ${JSON.stringify(playerText.slice(0, 20))}`);
      monitor.kickPlayer(id, Number(playerText));
      sendJson(res, 200, { kicked: { room: id, playerId: Number(playerText) } });
      return true;
    }
    return false;
  };
}
