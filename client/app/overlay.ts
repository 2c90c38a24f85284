// The page's message overlay: one place that tells the user what went wrong (no WebGPU, server unreachable, closed).
// DOM only; callers pass plain strings (set as text, never as HTML).

/** How serious a message is (colours the box). */
export type MessageKind = 'error' | 'info';

/** Shows a message box over the scene, replacing any previous one. */
export function showMessage(title: string, detail: string, kind: MessageKind = 'error', action?: { label: string; run: () => void }): void {
  const box = document.getElementById('message');
  if (!box) return;
  box.replaceChildren();
  box.className = `message ${kind}`;
  const h = document.createElement('h2');
  h.textContent = title;
  const p = document.createElement('p');
  p.textContent = detail;
  box.append(h, p);
  if (action) {
    const button = document.createElement('button');
    button.type = 'button';
    button.textContent = action.label;
    button.addEventListener('click', action.run);
    box.append(button);
  }
  box.hidden = false;
}

/** Hides the message box. */
export function hideMessage(): void {
  const box = document.getElementById('message');
  if (box) box.hidden = true;
}
