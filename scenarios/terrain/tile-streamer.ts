// Streams square terrain tiles (static triangle meshes of a height function) in around focus points — players first,
// then balls — and drops the ones no focus is near, never holding more than maxTiles. Deterministic: tiles are
// chosen in a fixed priority order and kept in a Map whose insertion order every run reproduces.
import type { Vec3Like } from '../../shared/physics/index.ts';
import type { Rgb, ScenarioContext } from '../../shared/sim/scenario.ts';
import { gridMesh, type HeightFn } from '../lib/terrain-grid.ts';

/** How the terrain is cut into tiles and how far it reaches. */
export interface TileGridOptions {
  heightAt: HeightFn;
  /** Cells per tile side (two triangles per cell). */
  tileCells: number;
  cellSizeMetres: number;
  /** Tiles exist only where they touch the disc of this radius around the origin. */
  terrainRadiusMetres: number;
  /** Colour of a tile from its mean height (m). */
  colorOf: (meanHeightMetres: number) => Rgb;
}

/** Streaming limits. */
export interface StreamLimits {
  /** Chebyshev radius (in tiles) wanted around each focus. */
  viewTiles: number;
  /** Most tiles loaded at once. */
  maxTiles: number;
  /** Most tiles built in one tick. */
  buildsPerTick: number;
}

const KEY_OFFSET = 32768;

function keyOf(tx: number, tz: number): number {
  return (tx + KEY_OFFSET) * 65536 + (tz + KEY_OFFSET);
}

function tileOfKey(key: number): { tx: number; tz: number } {
  return { tx: Math.floor(key / 65536) - KEY_OFFSET, tz: (key % 65536) - KEY_OFFSET };
}

/** The loaded tiles of one terrain. */
export class TileStreamer {
  private readonly grid: TileGridOptions;
  private readonly limits: StreamLimits;
  private readonly tileMetres: number;
  /** Loaded tiles: key → body id, in load order. */
  private tiles = new Map<number, number>();
  private loadedTotal = 0;
  private droppedTotal = 0;

  constructor(grid: TileGridOptions, limits: StreamLimits) {
    this.grid = grid;
    this.limits = limits;
    this.tileMetres = grid.tileCells * grid.cellSizeMetres;
  }

  /** Side of one tile (m). */
  get tileSizeMetres(): number {
    return this.tileMetres;
  }

  /** Number of loaded tiles. */
  get count(): number {
    return this.tiles.size;
  }

  /** Tiles loaded and dropped since the start. */
  get totals(): { loaded: number; dropped: number } {
    return { loaded: this.loadedTotal, dropped: this.droppedTotal };
  }

  /** Body ids of the loaded tiles, in load order. */
  bodyIds(): number[] {
    return [...this.tiles.values()];
  }

  /** The tile coordinates holding world (x, z). */
  tileAt(x: number, z: number): { tx: number; tz: number } {
    return { tx: Math.floor(x / this.tileMetres), tz: Math.floor(z / this.tileMetres) };
  }

  /** Whether the terrain reaches tile (tx, tz) (it touches the terrain disc). */
  inTerrain(tx: number, tz: number): boolean {
    const s = this.tileMetres;
    const nx = Math.max(tx * s, Math.min(0, (tx + 1) * s));
    const nz = Math.max(tz * s, Math.min(0, (tz + 1) * s));
    const r = this.grid.terrainRadiusMetres;
    return nx * nx + nz * nz <= r * r;
  }

  /** Whether the tile under world (x, z) is loaded. */
  isLoadedAt(x: number, z: number): boolean {
    const t = this.tileAt(x, z);
    return this.tiles.has(keyOf(t.tx, t.tz));
  }

  /** Tiles wanted for `foci`, most urgent first: every focus's own tile, then their first rings, and so on. */
  private wanted(foci: readonly Vec3Like[]): number[] {
    const out: number[] = [];
    const seen = new Set<number>();
    const centres = foci.map((f) => this.tileAt(f.x, f.z));
    for (let ring = 0; ring <= this.limits.viewTiles; ring++) {
      for (const c of centres) {
        for (let dz = -ring; dz <= ring; dz++) {
          for (let dx = -ring; dx <= ring; dx++) {
            if (Math.max(Math.abs(dx), Math.abs(dz)) !== ring) continue;
            const tx = c.tx + dx;
            const tz = c.tz + dz;
            const key = keyOf(tx, tz);
            if (seen.has(key) || !this.inTerrain(tx, tz)) continue;
            seen.add(key);
            out.push(key);
            if (out.length === this.limits.maxTiles) return out;
          }
        }
      }
    }
    return out;
  }

  /**
   * Brings the loaded set towards what `foci` need: drops tiles no focus is near (a tile one ring beyond the view
   * stays while there is room, so a focus wobbling on a tile edge does not churn), then builds missing wanted tiles
   * in priority order, at most `buildLimit` of them. Returns how many tiles it built and dropped.
   */
  update(ctx: ScenarioContext, foci: readonly Vec3Like[], buildLimit = this.limits.buildsPerTick): { built: number; dropped: number } {
    const wanted = this.wanted(foci);
    const wantedSet = new Set(wanted);
    const near = new Set<number>();
    const margin = this.limits.viewTiles + 1;
    for (const f of foci) {
      const c = this.tileAt(f.x, f.z);
      for (let dz = -margin; dz <= margin; dz++) for (let dx = -margin; dx <= margin; dx++) near.add(keyOf(c.tx + dx, c.tz + dz));
    }
    let room = this.limits.maxTiles - wanted.length;
    const next = new Map<number, number>();
    let dropped = 0;
    for (const [key, bodyId] of this.tiles) {
      if (wantedSet.has(key)) {
        next.set(key, bodyId);
      } else if (room > 0 && near.has(key)) {
        next.set(key, bodyId);
        room--;
      } else {
        if (ctx.world.getBody(bodyId)) ctx.remove(bodyId);
        dropped++;
      }
    }
    let built = 0;
    for (const key of wanted) {
      if (next.has(key)) continue;
      if (built >= buildLimit) break;
      next.set(key, this.build(ctx, key));
      built++;
    }
    this.tiles = next;
    this.loadedTotal += built;
    this.droppedTotal += dropped;
    return { built, dropped };
  }

  private build(ctx: ScenarioContext, key: number): number {
    const { tx, tz } = tileOfKey(key);
    const n = this.grid.tileCells;
    const mesh = gridMesh(this.grid.heightAt, tx * n, tz * n, n, n, this.grid.cellSizeMetres);
    let sum = 0;
    for (let i = 1; i < mesh.positions.length; i += 3) sum += mesh.positions[i];
    const mean = sum / (mesh.positions.length / 3);
    // Vertices are in world coordinates on the global lattice, so neighbouring tiles share their edges exactly.
    return ctx.spawn({ kind: 'mesh', positions: mesh.positions, indices: mesh.indices }, { x: 0, y: 0, z: 0 }, null, {
      motion: 'static',
      friction: 0.6,
      restitution: 0.3,
      color: this.grid.colorOf(mean),
      name: `tile ${tx},${tz}`,
    }).id;
  }

  /** [loaded total, dropped total, tile count, (key, body id) per tile in load order]. */
  save(): number[] {
    const out = [this.loadedTotal, this.droppedTotal, this.tiles.size];
    for (const [key, id] of this.tiles) out.push(key, id);
    return out;
  }

  /** Restores what save() wrote, starting at `state[at]`; returns the index after it. */
  restore(state: readonly number[], at: number): number {
    const n = state[at + 2];
    if (!Number.isInteger(n) || n < 0 || at + 3 + 2 * n > state.length) throw new Error('terrain-balls: bad saved tile state');
    this.loadedTotal = state[at];
    this.droppedTotal = state[at + 1];
    const tiles = new Map<number, number>();
    for (let i = 0; i < n; i++) tiles.set(state[at + 3 + 2 * i], state[at + 4 + 2 * i]);
    this.tiles = tiles;
    return at + 3 + 2 * n;
  }
}
