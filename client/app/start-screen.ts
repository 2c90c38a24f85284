// The start screen (lobby): lists the server's rooms (GET /api/rooms, scenario descriptions from GET /api/scenarios)
// with a Join button each, or offers the default room; offers "create room" and "join by code"
// (create-room-form.ts); resolves with the room the user picked and puts it in the address. DOM text only.
import { mountCreateRoom, mountJoinByCode, type ParamSummary, type ScenarioChoice } from './create-room-form.ts';

/** A room as GET /api/rooms describes it. */
export interface RoomSummary {
  id: string;
  scenario: string;
  clients: number;
  tick: number;
  bodies: number;
  /** With a fleet of servers: the one that hosts the room (joining it through this page is redirected there). */
  server?: { url: string };
  /** 'predict': the page runs the room's simulation itself; 'snapshot': it draws the server's snapshots. */
  netMode?: string;
  /** Why the room serves snapshots although predicted play was asked for or allowed. */
  netModeNote?: string;
}

/** A scenario as GET /api/scenarios describes it. */
export interface ScenarioSummary {
  name: string;
  description: string;
  /** Parameters with their ranges (empty when the server sent none). */
  params: Readonly<Record<string, ParamSummary>>;
}

/** What the user chose: a room id, or null for the server's default room. */
export interface JoinChoice {
  room: string | null;
}

async function getJson(url: string, signal: AbortSignal): Promise<unknown> {
  const res = await fetch(url, { signal, headers: { accept: 'application/json' } });
  if (!res.ok) throw new Error(`${url} answered ${res.status} ${res.statusText}`);
  return res.json();
}

/** Fetches the room list and scenario descriptions; throws a clear Error when the server can't be reached. */
export async function fetchLobby(baseUrl: string, timeoutMs = 5000): Promise<{ rooms: RoomSummary[]; scenarios: Map<string, ScenarioSummary> }> {
  const abort = new AbortController();
  const timer = setTimeout(() => abort.abort(), timeoutMs);
  try {
    const roomsJson = (await getJson(new URL('/api/rooms', baseUrl).href, abort.signal)) as { rooms?: unknown };
    const rooms = Array.isArray(roomsJson.rooms) ? roomsJson.rooms.filter(isRoomSummary) : [];
    const scenarios = new Map<string, ScenarioSummary>();
    try {
      const s = (await getJson(new URL('/api/scenarios', baseUrl).href, abort.signal)) as { scenarios?: unknown };
      if (Array.isArray(s.scenarios)) for (const sc of s.scenarios) if (isScenarioSummary(sc)) scenarios.set(sc.name, { name: sc.name, description: sc.description, params: validParams(sc.params) });
    } catch {
      // Descriptions are a nicety: the list still works without them.
    }
    return { rooms, scenarios };
  } catch (err) {
    const why = abort.signal.aborted ? `no answer within ${timeoutMs} ms` : (err as Error).message;
    throw new Error(`Cannot reach the server at ${baseUrl} (${why}).`);
  } finally {
    clearTimeout(timer);
  }
}

function isRoomSummary(v: unknown): v is RoomSummary {
  const r = v as RoomSummary;
  return !!r && typeof r.id === 'string' && typeof r.scenario === 'string' && typeof r.clients === 'number';
}

/** host:port of a server URL, for people (the URL itself when it does not parse). */
function hostOf(url: string): string {
  try {
    return new URL(url).host;
  } catch {
    return url;
  }
}

function isScenarioSummary(v: unknown): v is { name: string; description: string; params?: unknown } {
  const s = v as ScenarioSummary;
  return !!s && typeof s.name === 'string' && typeof s.description === 'string';
}

// Only well-formed parameter ranges reach the form (the server's answer is still data from the network).
function validParams(v: unknown): Record<string, ParamSummary> {
  const out: Record<string, ParamSummary> = {};
  if (!v || typeof v !== 'object') return out;
  for (const [name, spec] of Object.entries(v as Record<string, unknown>)) {
    const p = spec as ParamSummary;
    if (!p || ![p.default, p.min, p.max].every((n) => typeof n === 'number' && Number.isFinite(n)) || p.min > p.max) continue;
    out[name] = { default: p.default, min: p.min, max: p.max, integer: p.integer === true, description: typeof p.description === 'string' ? p.description : '' };
  }
  return out;
}

function el<K extends keyof HTMLElementTagNameMap>(tag: K, className: string, text?: string): HTMLElementTagNameMap[K] {
  const e = document.createElement(tag);
  if (className) e.className = className;
  if (text !== undefined) e.textContent = text;
  return e;
}

/** Shows the lobby in `root` and resolves when the user picks a room. */
export function showStartScreen(root: HTMLElement, lobby: { rooms: RoomSummary[]; scenarios: Map<string, ScenarioSummary> }): Promise<JoinChoice> {
  return new Promise((resolve) => {
    const list = root.querySelector('#rooms') as HTMLElement;
    list.replaceChildren();
    const pick = (room: string | null): void => {
      root.hidden = true;
      // The address names the room, so a reload rejoins it and "Back to rooms" leads here again.
      const url = new URL(location.href);
      url.searchParams.set('room', room ?? '');
      history.replaceState(null, '', url.href);
      resolve({ room });
    };
    const choices: ScenarioChoice[] = [...lobby.scenarios.values()];
    const create = root.querySelector('#create') as HTMLElement | null;
    if (create) mountCreateRoom(create, choices, pick);
    const byCode = root.querySelector('#join-by-code') as HTMLElement | null;
    if (byCode) mountJoinByCode(byCode, pick);
    if (lobby.rooms.length === 0) {
      const li = el('li', '');
      li.append(el('span', 'name', 'Default room'), el('span', 'desc', 'No rooms are open yet: joining starts the server’s default room.'));
      const b = el('button', '', 'Join');
      b.type = 'button';
      b.dataset.room = '';
      b.addEventListener('click', () => pick(null));
      li.append(b);
      list.append(li);
    }
    for (const room of lobby.rooms) {
      const li = el('li', '');
      const desc = lobby.scenarios.get(room.scenario)?.description ?? '';
      const mode = room.netMode === 'predict' ? 'predicted play' : 'snapshots';
      const host = typeof room.server?.url === 'string' ? ` · on ${hostOf(room.server.url)}` : '';
      li.append(el('span', 'name', `${room.id} · ${room.scenario}`), el('span', 'desc', desc), el('span', 'meta', `${room.clients} connected · ${room.bodies} bodies · tick ${room.tick} · ${mode}${host}`));
      if (room.netModeNote) li.append(el('span', 'meta', room.netModeNote));
      const b = el('button', '', 'Join');
      b.type = 'button';
      b.dataset.room = room.id;
      b.addEventListener('click', () => pick(room.id));
      li.append(b);
      list.append(li);
    }
    root.hidden = false;
    (list.querySelector('button') as HTMLButtonElement | null)?.focus();
  });
}
