// The monitor's page (GET /monitor): one self-contained HTML document with an inline script, so it works without the
// client build. It reads GET /monitor/events as a stream with fetch (so the admin token travels in the Authorization
// header, never in a URL), draws every room and its players, and posts the close and kick actions. Text via
// textContent only.

const STYLE = `
:root { color-scheme: dark; --bg: #101418; --panel: #1a2129; --muted: #8b98a5; --accent: #4aa3ff; --bad: #ff6b6b; --ok: #5fd38d; }
body { margin: 0; font: 14px/1.4 system-ui, sans-serif; background: var(--bg); color: #e6edf3; }
header { display: flex; gap: 16px; align-items: baseline; padding: 12px 20px; border-bottom: 1px solid #2a333d; }
h1 { font-size: 18px; margin: 0; }
#status { color: var(--muted); }
#status.bad { color: var(--bad); }
main { padding: 12px 20px; display: grid; gap: 12px; }
section.room { background: var(--panel); border-radius: 8px; padding: 12px 16px; }
section.room h2 { font-size: 16px; margin: 0 0 8px; display: flex; gap: 12px; align-items: center; }
section.room h2 .scenario { color: var(--muted); font-weight: normal; }
dl { display: grid; grid-template-columns: repeat(auto-fill, minmax(130px, 1fr)); gap: 4px 16px; margin: 0 0 8px; }
dt { color: var(--muted); font-size: 12px; }
dd { margin: 0; font-variant-numeric: tabular-nums; }
table { border-collapse: collapse; width: 100%; font-variant-numeric: tabular-nums; }
th, td { text-align: left; padding: 3px 8px; border-top: 1px solid #2a333d; }
th { color: var(--muted); font-weight: normal; font-size: 12px; }
button { background: #24303c; color: #e6edf3; border: 1px solid #3a4654; border-radius: 4px; padding: 2px 10px; cursor: pointer; }
button.danger { border-color: var(--bad); }
form { display: flex; gap: 8px; align-items: center; }
input { background: #0c1014; color: #e6edf3; border: 1px solid #3a4654; border-radius: 4px; padding: 3px 6px; width: 280px; }
.empty { color: var(--muted); }
`;

const SCRIPT = `
'use strict';
const statusEl = document.getElementById('status');
const roomsEl = document.getElementById('rooms');
const tokenForm = document.getElementById('token-form');
const tokenInput = document.getElementById('token');
let token = sessionStorage.getItem('taos-admin-token') || '';
let generation = 0;

function headers() { return token ? { authorization: 'Bearer ' + token } : {}; }
function setStatus(text, bad) { statusEl.textContent = text; statusEl.className = bad ? 'bad' : ''; }
function el(tag, text, cls) { const e = document.createElement(tag); if (text !== undefined) e.textContent = text; if (cls) e.className = cls; return e; }
function num(v, digits, unit) { return v === null || v === undefined ? '–' : v.toFixed(digits) + (unit ? ' ' + unit : ''); }
function mib(b) { return (b / 1048576).toFixed(1) + ' MiB'; }

async function act(url, what) {
  try {
    const res = await fetch(url, { method: 'POST', headers: headers() });
    const body = await res.json().catch(() => ({}));
    if (!res.ok) setStatus(what + ' failed: ' + (body.message || res.status), true);
  } catch (err) { setStatus(what + ' failed: ' + err.message, true); }
}

function stat(dl, label, value) { dl.append(el('dt', label), el('dd', value)); }

function drawRoom(r) {
  const s = el('section', undefined, 'room');
  s.dataset.room = r.id;
  const h = el('h2');
  h.append(el('span', r.id, 'id'), el('span', r.scenario, 'scenario'));
  if (r.closable) {
    const b = el('button', 'Close room', 'danger');
    b.dataset.action = 'close';
    b.addEventListener('click', () => act('/monitor/rooms/' + encodeURIComponent(r.id) + '/close', 'closing ' + r.id));
    h.append(b);
  }
  s.append(h);
  const dl = el('dl');
  stat(dl, 'net mode', r.netMode);
  stat(dl, 'tick', String(r.tick));
  stat(dl, 'ticks/s', num(r.ticksPerSecond, 1));
  if (r.tickMs || r.tickCpuMeanMs === null) stat(dl, 'tick p50 / p99', r.tickMs ? r.tickMs.p50.toFixed(2) + ' / ' + r.tickMs.p99.toFixed(2) + ' ms' : '–');
  else stat(dl, 'tick CPU (mean)', r.tickCpuMeanMs.toFixed(2) + ' ms');
  if (r.worker !== null) stat(dl, 'worker', '#' + r.worker);
  stat(dl, 'players', r.playerCount + (r.heldCount ? ' (' + r.heldCount + ' held)' : ''));
  stat(dl, 'bodies', String(r.bodies));
  stat(dl, 'WASM heap', r.wasmHeap ? mib(r.wasmHeap.usedBytes) + ' used, ' + mib(r.wasmHeap.freeBytes) + ' free' : '–');
  stat(dl, 'in / out', num(r.kbpsIn, 1) + ' / ' + num(r.kbpsOut, 1) + ' kbps');
  stat(dl, 'snapshots', r.snapshotRateHz + ' Hz');
  const params = Object.keys(r.params).map((k) => k + '=' + r.params[k]).join(' ');
  if (params) stat(dl, 'parameters', params);
  s.append(dl);
  if (r.players.length === 0) { s.append(el('p', 'No players connected.', 'empty')); return s; }
  const t = el('table');
  const head = el('tr');
  for (const c of ['player', 'name', 'RTT', 'input lead', 'late inputs', 'missed ticks', 'kbps in', 'kbps out', '']) head.append(el('th', c));
  t.append(head);
  for (const p of r.players) {
    const tr = el('tr');
    tr.dataset.player = String(p.playerId);
    tr.append(el('td', '#' + p.playerId), el('td', p.name), el('td', num(p.rttMs, 1, 'ms')), el('td', p.inputLeadTicks === null ? '–' : p.inputLeadTicks + ' ticks'),
      el('td', String(p.lateInputs)), el('td', String(p.missedInputTicks)), el('td', num(p.kbpsIn, 1)), el('td', num(p.kbpsOut, 1)));
    const td = el('td');
    const b = el('button', 'Kick', 'danger');
    b.dataset.action = 'kick';
    b.addEventListener('click', () => act('/monitor/rooms/' + encodeURIComponent(r.id) + '/players/' + p.playerId + '/kick', 'kicking #' + p.playerId));
    td.append(b);
    tr.append(td);
    t.append(tr);
  }
  s.append(t);
  return s;
}

function draw(state) {
  roomsEl.replaceChildren(...state.rooms.map(drawRoom));
  if (state.rooms.length === 0) roomsEl.append(el('p', 'No rooms are open.', 'empty'));
  setStatus('live · ' + state.rooms.length + ' room(s) · sampled ' + new Date().toLocaleTimeString());
}

async function listen() {
  const mine = ++generation;
  tokenForm.hidden = true;
  setStatus('connecting…');
  try {
    const res = await fetch('/monitor/events', { headers: headers() });
    if (res.status === 401 || res.status === 403) {
      const body = await res.json().catch(() => ({}));
      setStatus(body.message || 'the admin token is needed', true);
      tokenForm.hidden = false;
      tokenInput.focus();
      return;
    }
    if (!res.ok || !res.body) throw new Error('the server answered ' + res.status);
    const reader = res.body.pipeThrough(new TextDecoderStream()).getReader();
    let buffer = '';
    for (;;) {
      const { value, done } = await reader.read();
      if (done || mine !== generation) break;
      buffer += value;
      let end;
      while ((end = buffer.indexOf('\\n\\n')) >= 0) {
        const block = buffer.slice(0, end);
        buffer = buffer.slice(end + 2);
        const data = block.split('\\n').filter((l) => l.startsWith('data: ')).map((l) => l.slice(6)).join('\\n');
        if (data) draw(JSON.parse(data));
      }
    }
    if (mine === generation) throw new Error('the stream ended');
  } catch (err) {
    if (mine !== generation) return;
    setStatus('disconnected (' + err.message + '): retrying in 2 s', true);
    setTimeout(() => { if (mine === generation) listen(); }, 2000);
  }
}

tokenForm.addEventListener('submit', (e) => {
  e.preventDefault();
  token = tokenInput.value.trim();
  sessionStorage.setItem('taos-admin-token', token);
  listen();
});
listen();
`;

/** The monitor page. */
export const MONITOR_PAGE_HTML = `<!doctype html>
<html lang="en">
<head>
<meta charset="utf-8" />
<meta name="viewport" content="width=device-width, initial-scale=1" />
<title>taos-physics monitor</title>
<link rel="icon" href="data:," />
<style>${STYLE}</style>
</head>
<body>
<header>
<h1>taos-physics monitor</h1>
<span id="status">loading…</span>
<form id="token-form" hidden><label for="token">Admin token</label><input id="token" type="password" autocomplete="off" /><button type="submit">Connect</button></form>
</header>
<main id="rooms"></main>
<script>${SCRIPT}</script>
</body>
</html>
`;
