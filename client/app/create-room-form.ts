// The lobby's "create room" form (a scenario picker with each parameter's range from GET /api/scenarios, an optional
// room code, POST /api/rooms) and its "join by code" form. Resolves through callbacks with the room to join; refusals
// are shown under the form in the server's words. DOM text only.

/** A scenario parameter as GET /api/scenarios describes it. */
export interface ParamSummary {
  default: number;
  min: number;
  max: number;
  integer?: boolean;
  description: string;
}

/** A scenario with its parameters. */
export interface ScenarioChoice {
  name: string;
  description: string;
  params: Readonly<Record<string, ParamSummary>>;
}

/** Room ids the server accepts (server/room-manager.ts). */
export const ROOM_CODE_PATTERN = /^[A-Za-z0-9_-]{1,64}$/;

function el<K extends keyof HTMLElementTagNameMap>(tag: K, props: Partial<HTMLElementTagNameMap[K]> = {}, text?: string): HTMLElementTagNameMap[K] {
  const e = Object.assign(document.createElement(tag), props);
  if (text !== undefined) e.textContent = text;
  return e;
}

/** A short random room code (lowercase letters and digits). */
export function randomRoomCode(): string {
  const alphabet = 'abcdefghjkmnpqrstuvwxyz23456789';
  const bytes = crypto.getRandomValues(new Uint8Array(6));
  return Array.from(bytes, (b) => alphabet[b % alphabet.length]).join('');
}

/** Checks a parameter's value against its range; returns the problem in words, or null. */
export function paramProblem(name: string, spec: ParamSummary, value: number): string | null {
  if (!Number.isFinite(value)) return `${name} must be a number`;
  if (value < spec.min || value > spec.max) return `${name} must be between ${spec.min} and ${spec.max}`;
  if (spec.integer && !Number.isInteger(value)) return `${name} must be a whole number`;
  return null;
}

async function postRoom(scenario: string, params: Record<string, number>, roomId: string): Promise<string> {
  const res = await fetch('/api/rooms', { method: 'POST', headers: { 'content-type': 'application/json', accept: 'application/json' }, body: JSON.stringify({ scenario, params, roomId }) });
  const body = (await res.json().catch(() => ({}))) as { room?: { id?: string }; message?: string; error?: string };
  if (res.status === 401 || res.status === 403) throw new Error('This server lets only its operators create rooms (it has an admin token). Join an open room instead.');
  if (!res.ok) throw new Error(body.message ?? `the server answered ${res.status}`);
  return body.room?.id ?? roomId;
}

/** Builds the create-room form in `root`; `onCreated` gets the new room's id. */
export function mountCreateRoom(root: HTMLElement, scenarios: readonly ScenarioChoice[], onCreated: (roomId: string) => void): void {
  root.replaceChildren();
  if (scenarios.length === 0) return;
  const form = el('form', { id: 'create-room', noValidate: true });
  const picker = el('select', { id: 'scenario-picker', name: 'scenario' });
  for (const s of scenarios) picker.append(el('option', { value: s.name }, s.name));
  const desc = el('p', { className: 'desc' });
  const fields = el('div', { className: 'params' });
  const code = el('input', { id: 'room-code', name: 'roomId', placeholder: 'room code (optional)', maxLength: 64, autocomplete: 'off' });
  const create = el('button', { type: 'submit' }, 'Create room');
  const error = el('p', { className: 'form-error', hidden: true });
  error.setAttribute('role', 'alert');
  const pickerLabel = el('label', { className: 'row' });
  pickerLabel.append(el('span', {}, 'Scenario'), picker);
  const codeRow = el('div', { className: 'row' });
  codeRow.append(code, create);
  form.append(el('h2', {}, 'Create a room'), pickerLabel, desc, fields, codeRow, error);
  root.append(form);

  const inputs = new Map<string, HTMLInputElement>();
  const show = (): void => {
    const s = scenarios.find((x) => x.name === picker.value) ?? scenarios[0];
    desc.textContent = s.description;
    fields.replaceChildren();
    inputs.clear();
    for (const [name, spec] of Object.entries(s.params)) {
      const input = el('input', { type: 'number', name, id: `param-${name}`, min: String(spec.min), max: String(spec.max), step: spec.integer ? '1' : 'any', value: String(spec.default) });
      input.dataset.param = name;
      const label = el('label', { className: 'param', title: spec.description });
      label.append(el('span', { className: 'pname' }, name), input, el('span', { className: 'range' }, `${spec.min}–${spec.max}`), el('span', { className: 'pdesc' }, spec.description));
      fields.append(label);
      inputs.set(name, input);
    }
  };
  picker.addEventListener('change', show);
  show();

  form.addEventListener('submit', (e) => {
    e.preventDefault();
    const s = scenarios.find((x) => x.name === picker.value) ?? scenarios[0];
    const params: Record<string, number> = {};
    for (const [name, spec] of Object.entries(s.params)) {
      const value = Number(inputs.get(name)?.value);
      const problem = paramProblem(name, spec, value);
      if (problem) {
        error.textContent = problem;
        error.hidden = false;
        return;
      }
      if (value !== spec.default) params[name] = value;
    }
    const roomId = code.value.trim() || randomRoomCode();
    if (!ROOM_CODE_PATTERN.test(roomId)) {
      error.textContent = 'A room code is 1-64 letters, digits, - or _.';
      error.hidden = false;
      return;
    }
    create.disabled = true;
    error.hidden = true;
    postRoom(s.name, params, roomId).then(onCreated, (err: unknown) => {
      error.textContent = (err as Error).message;
      error.hidden = false;
      create.disabled = false;
    });
  });
}

/** Builds the join-by-code form in `root`; `onJoin` gets the code typed. */
export function mountJoinByCode(root: HTMLElement, onJoin: (roomId: string) => void): void {
  root.replaceChildren();
  const form = el('form', { id: 'join-code-form', noValidate: true, className: 'row' });
  const input = el('input', { id: 'join-code', name: 'code', placeholder: 'room code', maxLength: 64, autocomplete: 'off' });
  const error = el('p', { className: 'form-error', hidden: true });
  form.append(input, el('button', { type: 'submit', className: 'secondary' }, 'Join by code'));
  root.append(form, error);
  form.addEventListener('submit', (e) => {
    e.preventDefault();
    const code = input.value.trim();
    if (!ROOM_CODE_PATTERN.test(code)) {
      error.textContent = 'A room code is 1-64 letters, digits, - or _.';
      error.hidden = false;
      return;
    }
    onJoin(code);
  });
}
