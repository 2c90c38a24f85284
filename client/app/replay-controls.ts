// The replay viewer's controls (replay.html): file picker and drag and drop, play/pause, the tick scrubber, speed,
// the followed player, keys (space plays, ←/→ step a tick) and orbit dragging. DOM in, callbacks out; no state.
import type { ReplayPlayer } from '../physics/replay-player.ts';

/** What the controls ask the page to do. */
export interface ReplayActions {
  open(bytes: Uint8Array, name: string): void;
  togglePlay(): void;
  scrub(tick: number): void;
  stepBy(ticks: number): void;
  speed(multiplier: number): void;
  follow(playerId: number | null): void;
  orbitDrag(dxPx: number, dyPx: number): void;
  orbitZoom(deltaY: number): void;
}

/** What the page tells the controls to show. */
export interface ReplayControls {
  setLog(name: string, player: ReplayPlayer | null): void;
  setStatus(text: string, tone: 'good' | 'bad' | null): void;
  setTick(tick: number, lastTick: number): void;
  setPlaying(playing: boolean): void;
  setFollow(playerId: number | null): void;
}

const byId = <T extends HTMLElement>(id: string): T => {
  const e = document.getElementById(id);
  if (!e) throw new Error(`page is missing #${id}`);
  return e as T;
};

/** Wires the page's controls to `actions`. */
export function bindReplayControls(actions: ReplayActions): ReplayControls {
  const file = byId<HTMLInputElement>('log-file');
  const play = byId<HTMLButtonElement>('play');
  const scrub = byId<HTMLInputElement>('scrub');
  const tickLabel = byId('tick-label');
  const speed = byId<HTMLSelectElement>('speed');
  const follow = byId<HTMLSelectElement>('follow');
  const status = byId('verify-status');
  const logName = byId('log-name');
  const dropZone = byId('drop-zone');
  const canvas = byId<HTMLCanvasElement>('scene');

  const openFile = (f: File): void => {
    f.arrayBuffer().then(
      (buf) => actions.open(new Uint8Array(buf), f.name),
      (err: unknown) => {
        status.textContent = `Cannot read ${f.name}: ${(err as Error).message}`;
      },
    );
  };
  file.addEventListener('change', () => {
    const f = file.files?.[0];
    if (f) openFile(f);
    file.value = '';
  });
  window.addEventListener('dragover', (e) => {
    e.preventDefault();
    dropZone.hidden = false;
  });
  window.addEventListener('dragleave', (e) => {
    if (e.relatedTarget === null) dropZone.hidden = true;
  });
  window.addEventListener('drop', (e) => {
    e.preventDefault();
    dropZone.hidden = true;
    const f = e.dataTransfer?.files[0];
    if (f) openFile(f);
  });
  play.addEventListener('click', () => actions.togglePlay());
  scrub.addEventListener('input', () => actions.scrub(Number(scrub.value)));
  speed.addEventListener('change', () => actions.speed(Number(speed.value)));
  follow.addEventListener('change', () => actions.follow(follow.value === '' ? null : Number(follow.value)));
  window.addEventListener('keydown', (e) => {
    if (e.target instanceof HTMLInputElement || e.target instanceof HTMLSelectElement) return;
    if (e.code === 'Space') {
      e.preventDefault();
      actions.togglePlay();
    } else if (e.code === 'ArrowRight') actions.stepBy(1);
    else if (e.code === 'ArrowLeft') actions.stepBy(-1);
  });
  canvas.addEventListener('mousemove', (e) => {
    if ((e.buttons & 1) !== 0) actions.orbitDrag(e.movementX, e.movementY);
  });
  canvas.addEventListener('wheel', (e) => actions.orbitZoom(e.deltaY), { passive: true });

  return {
    setLog(name, player) {
      logName.textContent = player ? `${name} · ${player.header.scenario} · ${player.totalTicks} ticks · seed ${String(player.header.seed)}` : name;
      follow.replaceChildren(new Option('orbit camera', ''));
      for (const p of player?.playersInLog() ?? []) follow.append(new Option(`#${p.playerId} ${p.name}`, String(p.playerId)));
      const ready = player !== null;
      play.disabled = !ready;
      scrub.disabled = !ready;
      scrub.max = String(player?.totalTicks ?? 0);
    },
    setStatus(text, tone) {
      status.textContent = text;
      status.className = tone ?? '';
    },
    setTick(tick, lastTick) {
      scrub.max = String(lastTick);
      scrub.value = String(tick);
      tickLabel.textContent = `tick ${tick} / ${lastTick}`;
    },
    setPlaying(playing) {
      play.textContent = playing ? 'Pause' : 'Play';
    },
    setFollow(playerId) {
      follow.value = playerId === null ? '' : String(playerId);
    },
  };
}
