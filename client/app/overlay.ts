// The page's message overlay: one place that tells the user what went wrong (no WebGPU, server unreachable, closed).
// DOM only; callers pass plain strings (set as text, never as HTML).

/** How serious a message is (colours the box). */
export type MessageKind = 'error' | 'info';

/** A button under a message. */
export interface MessageAction {
  label: string;
  run: () => void;
}

/** Shows a message box over the scene, replacing any previous one, with its buttons in order. */
export function showMessage(title: string, detail: string, kind: MessageKind = 'error', action?: MessageAction | readonly MessageAction[]): void {
  const box = document.getElementById('message');
  if (!box) return;
  box.replaceChildren();
  box.className = `message ${kind}`;
  const h = document.createElement('h2');
  h.textContent = title;
  const p = document.createElement('p');
  p.textContent = detail;
  box.append(h, p);
  const actions = action === undefined ? [] : Array.isArray(action) ? (action as readonly MessageAction[]) : [action as MessageAction];
  if (actions.length > 0) {
    const row = document.createElement('div');
    row.className = 'actions';
    for (const a of actions) {
      const button = document.createElement('button');
      button.type = 'button';
      button.textContent = a.label;
      button.addEventListener('click', a.run);
      row.append(button);
    }
    box.append(row);
  }
  box.hidden = false;
}

/** Hides the message box. */
export function hideMessage(): void {
  const box = document.getElementById('message');
  if (box) box.hidden = true;
}
