// The WebGPU scene renderer: one pipeline, a depth buffer, meshes uploaded once per shape, static instances uploaded
// when they change, and every dynamic transform written per frame into one instance buffer. Owns its GPU objects.
import { initGpu, type AdapterSummary, type GpuContext } from './gpu-context.ts';
import { InstanceStore, type BodyRegistration, type BodyStyle, type PackedInstances } from './instance-store.ts';
import { mat4LookAt, mat4Multiply, mat4Perspective, type Vec3 } from './mat4.ts';
import type { MeshData } from './mesh-data.ts';
import { FRAME_UNIFORM_FLOATS, INSTANCE_STRIDE_BYTES, SCENE_SHADER_WGSL, VERTEX_STRIDE_BYTES } from './shaders.ts';
import { shapeMeshRef } from './shape-mesh.ts';
import type { ShapeSpec } from '../../shared/physics-data/shape-spec.ts';

/** Where the camera is and what it sees. */
export interface CameraView {
  eye: Vec3;
  target: Vec3;
  fovYRadians: number;
  nearMetres: number;
  farMetres: number;
}

/** Lighting and atmosphere; colours are sRGB in [0, 1]. */
export interface SceneLighting {
  /** Direction the sunlight travels (need not be unit length). */
  lightDirection: Vec3;
  lightColor: Vec3;
  skyColor: Vec3;
  groundColor: Vec3;
  clearColor: Vec3;
  fogDensityPerMetre: number;
  gridCellMetres: number;
  gridMajorEvery: number;
}

/** What one frame cost. */
export interface FrameStats {
  drawCalls: number;
  instances: number;
  triangles: number;
  widthPx: number;
  heightPx: number;
}

/** A body to draw: its shape, whether it is static, its look, and (for static bodies) its pose. */
export interface RenderBodySpec extends Omit<BodyRegistration, 'mesh' | 'style'> {
  shape: ShapeSpec;
  style?: Partial<BodyStyle>;
}

interface GpuMesh {
  vertexBuffer: GPUBuffer;
  indexBuffer: GPUBuffer;
  indexCount: number;
}

const DEFAULT_LIGHTING: SceneLighting = {
  lightDirection: [-0.45, -1, -0.3],
  lightColor: [1.15, 1.1, 1.0],
  skyColor: [0.42, 0.47, 0.55],
  groundColor: [0.22, 0.2, 0.18],
  clearColor: [0.63, 0.73, 0.84],
  fogDensityPerMetre: 0.006,
  gridCellMetres: 1,
  gridMajorEvery: 10,
};

/** The sRGB decode (display value → linear), as the shader does it, for uniforms and clear values. */
function srgbToLinear(v: number): number {
  return v <= 0.04045 ? v / 12.92 : Math.pow((v + 0.055) / 1.055, 2.4);
}

const DEFAULT_STYLE: BodyStyle = { color: [0.7, 0.7, 0.72], emissive: 0, flags: 0, visible: true };
const DEPTH_FORMAT: GPUTextureFormat = 'depth24plus';

/** Renders the bodies it is told about; create with Renderer.create(canvas). Call destroy() when done. */
export class Renderer {
  readonly adapter: AdapterSummary;
  /** Resolves with a reason if the GPU device is lost. */
  readonly lost: Promise<string>;
  readonly store = new InstanceStore();
  lighting: SceneLighting = { ...DEFAULT_LIGHTING };
  /** Upper bound on devicePixelRatio used for the backing store (software renderers are slow). */
  maxPixelRatio = 2;

  private readonly canvas: HTMLCanvasElement;
  private readonly gpu: GpuContext;
  private readonly pipeline: GPURenderPipeline;
  private readonly frameBuffer: GPUBuffer;
  private readonly bindGroup: GPUBindGroup;
  private readonly frameData = new Float32Array(FRAME_UNIFORM_FLOATS);
  private readonly meshes = new Map<string, GpuMesh>();
  private depthTexture: GPUTexture | null = null;
  private staticBuffer: GPUBuffer | null = null;
  private staticPacked: PackedInstances = { data: new Float32Array(0), count: 0, ranges: [] };
  private dynamicBuffer: GPUBuffer | null = null;
  private destroyed = false;
  /** True when the target has no sRGB view and the shader must encode gamma itself. */
  private readonly encodesInShader: boolean;

  private constructor(canvas: HTMLCanvasElement, gpu: GpuContext) {
    this.canvas = canvas;
    this.gpu = gpu;
    this.encodesInShader = !gpu.viewFormat.endsWith('-srgb');
    this.adapter = gpu.adapter;
    this.lost = gpu.lost;
    const device = gpu.device;
    const module = device.createShaderModule({ label: 'scene shader', code: SCENE_SHADER_WGSL });
    const instanceAttribute = (location: number, index: number): GPUVertexAttribute => ({ shaderLocation: location, offset: index * 16, format: 'float32x4' });
    this.pipeline = device.createRenderPipeline({
      label: 'scene pipeline',
      layout: 'auto',
      vertex: {
        module,
        entryPoint: 'vsMain',
        buffers: [
          {
            arrayStride: VERTEX_STRIDE_BYTES,
            stepMode: 'vertex',
            attributes: [
              { shaderLocation: 0, offset: 0, format: 'float32x3' },
              { shaderLocation: 1, offset: 12, format: 'float32x3' },
            ],
          },
          {
            arrayStride: INSTANCE_STRIDE_BYTES,
            stepMode: 'instance',
            attributes: [instanceAttribute(2, 0), instanceAttribute(3, 1), instanceAttribute(4, 2), instanceAttribute(5, 3)],
          },
        ],
      },
      fragment: { module, entryPoint: 'fsMain', targets: [{ format: gpu.viewFormat }], constants: { ENCODE_SRGB: this.encodesInShader ? 1 : 0 } },
      primitive: { topology: 'triangle-list', cullMode: 'back', frontFace: 'ccw' },
      depthStencil: { format: DEPTH_FORMAT, depthWriteEnabled: true, depthCompare: 'less' },
    });
    this.frameBuffer = device.createBuffer({ label: 'frame uniforms', size: FRAME_UNIFORM_FLOATS * 4, usage: GPUBufferUsage.UNIFORM | GPUBufferUsage.COPY_DST });
    this.bindGroup = device.createBindGroup({ layout: this.pipeline.getBindGroupLayout(0), entries: [{ binding: 0, resource: { buffer: this.frameBuffer } }] });
  }

  /** Starts WebGPU on the canvas and builds the pipeline; throws WebGpuUnavailableError without WebGPU. */
  static async create(canvas: HTMLCanvasElement): Promise<Renderer> {
    const gpu = await initGpu(canvas);
    return new Renderer(canvas, gpu);
  }

  /** Adds a body to draw. Throws a clear Error for a bad shape or a duplicate id (nothing is added then). */
  addBody(id: number, spec: RenderBodySpec): void {
    this.assertAlive();
    const mesh = shapeMeshRef(spec.shape, `body ${id}`);
    // Build the mesh before registering, so a shape that fails to triangulate leaves no trace.
    const built = this.meshes.has(mesh.key) ? null : mesh.build();
    const isNew = this.store.add(id, { mesh, isStatic: spec.isStatic, style: { ...DEFAULT_STYLE, ...spec.style }, position: spec.position, rotation: spec.rotation });
    if (isNew && built) this.meshes.set(mesh.key, this.upload(mesh.key, built));
  }

  /** Stops drawing a body and frees its mesh if nothing else uses it. */
  removeBody(id: number): void {
    const freed = this.store.remove(id);
    if (freed) {
      const mesh = this.meshes.get(freed);
      mesh?.vertexBuffer.destroy();
      mesh?.indexBuffer.destroy();
      this.meshes.delete(freed);
    }
  }

  /** Draws one frame from the camera; dynamic poses are whatever was last set with store.setPose(). */
  render(camera: CameraView): FrameStats {
    this.assertAlive();
    const device = this.gpu.device;
    const { width, height } = this.resize();
    this.writeFrameUniforms(camera, width / height);

    if (this.store.takeStaticDirty()) {
      this.staticPacked = this.store.packStatic();
      this.staticBuffer = this.ensureBuffer(this.staticBuffer, this.staticPacked.data.byteLength, 'static instances');
      device.queue.writeBuffer(this.staticBuffer, 0, this.staticPacked.data);
    }
    const dynamic = this.store.packDynamic();
    const dynamicBytes = dynamic.count * INSTANCE_STRIDE_BYTES;
    if (dynamic.count > 0) {
      this.dynamicBuffer = this.ensureBuffer(this.dynamicBuffer, dynamicBytes, 'dynamic instances');
      device.queue.writeBuffer(this.dynamicBuffer, 0, dynamic.data.buffer, dynamic.data.byteOffset, dynamicBytes);
    }

    const encoder = device.createCommandEncoder({ label: 'frame' });
    // Clear values are in the target's space: linear through an sRGB view, display values otherwise.
    const c = this.encodesInShader ? this.lighting.clearColor : this.lighting.clearColor.map(srgbToLinear);
    const pass = encoder.beginRenderPass({
      colorAttachments: [{ view: this.gpu.context.getCurrentTexture().createView({ format: this.gpu.viewFormat }), clearValue: { r: c[0], g: c[1], b: c[2], a: 1 }, loadOp: 'clear', storeOp: 'store' }],
      depthStencilAttachment: { view: this.depthView(width, height), depthClearValue: 1, depthLoadOp: 'clear', depthStoreOp: 'store' },
    });
    pass.setPipeline(this.pipeline);
    pass.setBindGroup(0, this.bindGroup);
    const stats: FrameStats = { drawCalls: 0, instances: 0, triangles: 0, widthPx: width, heightPx: height };
    this.drawRanges(pass, this.staticBuffer, this.staticPacked, stats);
    this.drawRanges(pass, this.dynamicBuffer, dynamic, stats);
    pass.end();
    device.queue.submit([encoder.finish()]);
    return stats;
  }

  /** Frees every GPU object this renderer made (the device too). */
  destroy(): void {
    if (this.destroyed) return;
    this.destroyed = true;
    for (const mesh of this.meshes.values()) {
      mesh.vertexBuffer.destroy();
      mesh.indexBuffer.destroy();
    }
    this.meshes.clear();
    this.staticBuffer?.destroy();
    this.dynamicBuffer?.destroy();
    this.depthTexture?.destroy();
    this.frameBuffer.destroy();
    this.gpu.context.unconfigure();
    this.gpu.device.destroy();
  }

  private assertAlive(): void {
    if (this.destroyed) throw new Error('renderer: used after destroy()');
  }

  private drawRanges(pass: GPURenderPassEncoder, buffer: GPUBuffer | null, packed: PackedInstances, stats: FrameStats): void {
    if (!buffer || packed.count === 0) return;
    pass.setVertexBuffer(1, buffer);
    for (const range of packed.ranges) {
      const mesh = this.meshes.get(range.key);
      if (!mesh) continue;
      pass.setVertexBuffer(0, mesh.vertexBuffer);
      pass.setIndexBuffer(mesh.indexBuffer, 'uint32');
      pass.drawIndexed(mesh.indexCount, range.count, 0, 0, range.first);
      stats.drawCalls++;
      stats.instances += range.count;
      stats.triangles += (mesh.indexCount / 3) * range.count;
    }
  }

  private upload(key: string, mesh: MeshData): GpuMesh {
    const device = this.gpu.device;
    const vertexCount = mesh.positions.length / 3;
    const interleaved = new Float32Array(vertexCount * 6);
    for (let v = 0; v < vertexCount; v++) {
      interleaved.set(mesh.positions.subarray(v * 3, v * 3 + 3), v * 6);
      interleaved.set(mesh.normals.subarray(v * 3, v * 3 + 3), v * 6 + 3);
    }
    const vertexBuffer = device.createBuffer({ label: `${key} vertices`, size: interleaved.byteLength, usage: GPUBufferUsage.VERTEX | GPUBufferUsage.COPY_DST });
    device.queue.writeBuffer(vertexBuffer, 0, interleaved);
    // Index buffers must be a multiple of 4 bytes: uint32 indices always are.
    const indexBuffer = device.createBuffer({ label: `${key} indices`, size: mesh.indices.byteLength, usage: GPUBufferUsage.INDEX | GPUBufferUsage.COPY_DST });
    device.queue.writeBuffer(indexBuffer, 0, mesh.indices);
    return { vertexBuffer, indexBuffer, indexCount: mesh.indices.length };
  }

  private ensureBuffer(buffer: GPUBuffer | null, sizeBytes: number, label: string): GPUBuffer {
    const needed = Math.max(INSTANCE_STRIDE_BYTES, sizeBytes);
    if (buffer && buffer.size >= needed) return buffer;
    buffer?.destroy();
    let size = INSTANCE_STRIDE_BYTES * 64;
    while (size < needed) size *= 2;
    return this.gpu.device.createBuffer({ label, size, usage: GPUBufferUsage.VERTEX | GPUBufferUsage.COPY_DST });
  }

  private resize(): { width: number; height: number } {
    const dpr = Math.min(globalThis.devicePixelRatio || 1, this.maxPixelRatio);
    const cssW = this.canvas.clientWidth || this.canvas.width;
    const cssH = this.canvas.clientHeight || this.canvas.height;
    const width = Math.max(1, Math.min(8192, Math.round(cssW * dpr)));
    const height = Math.max(1, Math.min(8192, Math.round(cssH * dpr)));
    if (this.canvas.width !== width) this.canvas.width = width;
    if (this.canvas.height !== height) this.canvas.height = height;
    return { width, height };
  }

  private depthView(width: number, height: number): GPUTextureView {
    if (!this.depthTexture || this.depthTexture.width !== width || this.depthTexture.height !== height) {
      this.depthTexture?.destroy();
      this.depthTexture = this.gpu.device.createTexture({ label: 'depth', size: [width, height], format: DEPTH_FORMAT, usage: GPUTextureUsage.RENDER_ATTACHMENT });
    }
    return this.depthTexture.createView();
  }

  private writeFrameUniforms(camera: CameraView, aspect: number): void {
    const f = this.frameData;
    const proj = mat4Perspective(camera.fovYRadians, aspect, camera.nearMetres, camera.farMetres);
    const view = mat4LookAt(camera.eye, camera.target, [0, 1, 0]);
    f.set(mat4Multiply(proj, view), 0);
    const L = this.lighting;
    const d = L.lightDirection;
    const len = Math.sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]) || 1;
    f.set([camera.eye[0], camera.eye[1], camera.eye[2], 1], 16);
    f.set([d[0] / len, d[1] / len, d[2] / len, 0], 20);
    f.set([...L.lightColor, 1], 24);
    f.set([...L.skyColor, 1], 28);
    f.set([...L.groundColor, 1], 32);
    f.set([...L.clearColor.map(srgbToLinear), L.fogDensityPerMetre], 36);
    f.set([L.gridCellMetres, L.gridMajorEvery, 0.06, 0], 40);
    this.gpu.device.queue.writeBuffer(this.frameBuffer, 0, f);
  }
}
