// Tests for server/metrics.ts: per-server registries and the Prometheus text they render.
import { describe, expect, it } from 'vitest';
import { createMetrics, renderMetrics } from '../../server/metrics.ts';

describe('metrics', () => {
  it('renders the tick, input, snapshot and traffic metrics in Prometheus format', async () => {
    const m = createMetrics({ processMetrics: false });
    m.tickDuration.observe(0.004);
    m.physicsStep.observe(0.003);
    m.inputsLate.inc(2);
    m.snapshotBytes.observe(321);
    m.bytesSent.inc(321);
    m.rooms.set(1);
    const { body, contentType } = await renderMetrics(m);
    expect(contentType).toMatch(/text\/plain/);
    expect(body).toContain('taos_tick_duration_seconds_bucket{le="0.008"} 1');
    expect(body).toContain('taos_physics_step_seconds_count 1');
    expect(body).toContain('taos_inputs_late_total 2');
    expect(body).toContain('taos_snapshot_bytes_sum 321');
    expect(body).toContain('taos_bytes_sent_total 321');
    expect(body).toContain('taos_rooms 1');
    expect(body).toContain('# TYPE taos_snapshots_skipped_total counter');
  });

  it('keeps two servers\' counters apart and can include process metrics', async () => {
    const a = createMetrics({ processMetrics: true });
    const b = createMetrics({ processMetrics: false });
    a.ticks.inc(5);
    expect((await renderMetrics(a)).body).toContain('taos_ticks_total 5');
    expect((await renderMetrics(a)).body).toContain('taos_process_cpu_user_seconds_total');
    expect((await renderMetrics(a)).body).toMatch(/^taos_nodejs_external_memory_bytes \d+/m);
    expect((await renderMetrics(b)).body).toContain('taos_ticks_total 0');
  });

  it('labels each room\'s WASM heap with the room id and drops a room once its source no longer lists it', async () => {
    const m = createMetrics({ processMetrics: false });
    let rooms = [
      { room: 'default', usedBytes: 10_000_000, freeBytes: 124_217_728 },
      { room: 'arena', usedBytes: 20_000_000, freeBytes: 114_217_728 },
    ];
    m.setRoomHeapSource(() => rooms);
    let body = (await renderMetrics(m)).body;
    expect(body).toContain('taos_room_wasm_heap_bytes{room="default",kind="used"} 10000000');
    expect(body).toContain('taos_room_wasm_heap_bytes{room="arena",kind="free"} 114217728');
    rooms = rooms.slice(0, 1);
    body = (await renderMetrics(m)).body;
    expect(body).toContain('taos_room_wasm_heap_bytes{room="default",kind="free"} 124217728');
    expect(body).not.toContain('room="arena"');
  });
});
