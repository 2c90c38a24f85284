// Name tags over the other players' characters: a DOM label per character, placed each frame where its head projects
// on the canvas (hidden behind the camera or off screen). Names come from join events and, for players who were
// there before us, from GET /api/rooms/ID/players; an unknown player reads "#id". Text via textContent only.
import type { SnapshotView } from '../../shared/protocol/snapshot-frame.ts';
import type { SimEvent } from '../../shared/sim/types.ts';
import { mat4LookAt, mat4Multiply, mat4Perspective, mat4TransformPoint, type Vec3 } from '../render/mat4.ts';
import type { CameraView } from '../render/renderer.ts';

/** Where the tag sits above a character's feet (m). */
const TAG_HEIGHT_METRES = 2.2;
/** Tags farther than this (m) are not shown. */
const MAX_TAG_DISTANCE_METRES = 60;

/** The labels of one session. */
export class NameTags {
  private readonly root: HTMLElement;
  private readonly ownPlayerId: number;
  private readonly names = new Map<number, string>();
  private readonly tags = new Map<number, HTMLDivElement>();

  constructor(root: HTMLElement, ownPlayerId: number) {
    this.root = root;
    this.ownPlayerId = ownPlayerId;
    root.replaceChildren();
    root.hidden = false;
  }

  /** Learns the names of the players already in the room (best effort: a failure leaves "#id" tags). */
  async fetchNames(roomId: string): Promise<void> {
    try {
      const res = await fetch(`/api/rooms/${encodeURIComponent(roomId)}/players`, { headers: { accept: 'application/json' } });
      if (!res.ok) return;
      const body = (await res.json()) as { players?: Array<{ playerId?: unknown; name?: unknown }> };
      for (const p of body.players ?? []) if (typeof p.playerId === 'number' && typeof p.name === 'string' && !this.names.has(p.playerId)) this.names.set(p.playerId, p.name);
    } catch {
      // Names are a nicety; the tags show ids.
    }
  }

  /** Takes names from join events. */
  onEvent(e: SimEvent): void {
    if (e.type === 'playerJoined') this.names.set(e.playerId, e.name);
  }

  /** The name shown for a player. */
  nameOf(playerId: number): string {
    return this.names.get(playerId) ?? `#${playerId}`;
  }

  /** Places the tags for this frame. */
  update(view: SnapshotView | null, camera: CameraView, widthPx: number, heightPx: number): void {
    const seen = new Set<number>();
    if (view && widthPx > 0 && heightPx > 0 && view.characters.some((c) => c.playerId !== this.ownPlayerId)) {
      const viewMatrix = mat4LookAt(camera.eye, camera.target, [0, 1, 0]);
      const clip = mat4Multiply(mat4Perspective(camera.fovYRadians, widthPx / heightPx, camera.nearMetres, camera.farMetres), viewMatrix);
      for (const c of view.characters) {
        if (c.playerId === this.ownPlayerId) continue;
        const head: Vec3 = [c.position.x, c.position.y + TAG_HEIGHT_METRES, c.position.z];
        const local = mat4TransformPoint(viewMatrix, head);
        if (local[2] >= -camera.nearMetres || -local[2] > MAX_TAG_DISTANCE_METRES) continue;
        const p = mat4TransformPoint(clip, head);
        if (Math.abs(p[0]) > 1.1 || Math.abs(p[1]) > 1.1) continue;
        seen.add(c.playerId);
        let tag = this.tags.get(c.playerId);
        if (!tag) {
          tag = document.createElement('div');
          tag.className = 'tag';
          tag.dataset.player = String(c.playerId);
          this.root.append(tag);
          this.tags.set(c.playerId, tag);
        }
        const text = this.nameOf(c.playerId);
        if (tag.textContent !== text) tag.textContent = text;
        tag.style.transform = `translate(${(((p[0] + 1) / 2) * 100).toFixed(2)}vw, ${(((1 - p[1]) / 2) * 100).toFixed(2)}vh) translate(-50%, -100%)`;
        tag.hidden = false;
      }
    }
    for (const [id, tag] of this.tags) if (!seen.has(id)) tag.hidden = true;
  }

  /** Removes every tag. */
  clear(): void {
    this.root.replaceChildren();
    this.tags.clear();
  }
}
