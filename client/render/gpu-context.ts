// WebGPU start-up: adapter, device and canvas context, with a clear, typed error when the browser can't do WebGPU.
// Owns nothing else; the renderer builds its pipeline on the device this returns.

/** Why WebGPU is unavailable, for messages the page shows. */
export const GpuFailure = {
  NoApi: 'no-api',
  InsecureContext: 'insecure-context',
  NoAdapter: 'no-adapter',
  NoDevice: 'no-device',
  NoContext: 'no-context',
} as const;

export type GpuFailureReason = (typeof GpuFailure)[keyof typeof GpuFailure];

/** Thrown when this browser cannot give us a WebGPU device; `reason` says which step failed. */
export class WebGpuUnavailableError extends Error {
  readonly reason: GpuFailureReason;
  constructor(reason: GpuFailureReason, message: string) {
    super(message);
    this.name = 'WebGpuUnavailableError';
    this.reason = reason;
  }
}

/** What the adapter says about itself (shown in the HUD and the test hook). */
export interface AdapterSummary {
  vendor: string;
  architecture: string;
  device: string;
  description: string;
  isFallbackAdapter: boolean;
}

/** A ready device and a configured canvas context. */
export interface GpuContext {
  device: GPUDevice;
  context: GPUCanvasContext;
  format: GPUTextureFormat;
  /** The format to render through: the sRGB view of `format` when there is one (the GPU then encodes gamma). */
  viewFormat: GPUTextureFormat;
  adapter: AdapterSummary;
  /** Resolves when the device is lost (never, normally); the message says why. */
  lost: Promise<string>;
}

/** Requests an adapter and device and configures `canvas` for them; throws WebGpuUnavailableError on failure. */
export async function initGpu(canvas: HTMLCanvasElement): Promise<GpuContext> {
  const gpu = (navigator as Navigator & { gpu?: GPU }).gpu;
  if (!gpu) {
    if (typeof isSecureContext === 'boolean' && !isSecureContext) {
      throw new WebGpuUnavailableError(GpuFailure.InsecureContext, 'WebGPU needs a secure page: open it over https or from localhost/127.0.0.1.');
    }
    throw new WebGpuUnavailableError(GpuFailure.NoApi, 'This browser has no WebGPU (navigator.gpu is missing). Use a recent Chrome, Edge or Safari, or Firefox with WebGPU enabled.');
  }
  let adapter: GPUAdapter | null;
  try {
    adapter = await gpu.requestAdapter({ powerPreference: 'high-performance' });
  } catch (err) {
    throw new WebGpuUnavailableError(GpuFailure.NoAdapter, `WebGPU could not find a graphics adapter: ${(err as Error).message}`);
  }
  if (!adapter) {
    throw new WebGpuUnavailableError(GpuFailure.NoAdapter, 'WebGPU is present but offered no graphics adapter (it may be disabled or blocklisted for this GPU).');
  }
  let device: GPUDevice;
  try {
    device = await adapter.requestDevice();
  } catch (err) {
    throw new WebGpuUnavailableError(GpuFailure.NoDevice, `WebGPU could not create a device: ${(err as Error).message}`);
  }
  const context = canvas.getContext('webgpu');
  if (!context) {
    device.destroy();
    throw new WebGpuUnavailableError(GpuFailure.NoContext, 'The canvas refused a WebGPU context.');
  }
  const format = gpu.getPreferredCanvasFormat();
  const srgbView: GPUTextureFormat | null = format === 'bgra8unorm' ? 'bgra8unorm-srgb' : format === 'rgba8unorm' ? 'rgba8unorm-srgb' : null;
  context.configure({ device, format, alphaMode: 'opaque', viewFormats: srgbView ? [srgbView] : [] });
  device.addEventListener('uncapturederror', (event) => {
    console.error(`WebGPU error: ${(event as GPUUncapturedErrorEvent).error.message}`);
  });
  const lost = device.lost.then((info) => `${info.reason}: ${info.message}`);
  return { device, context, format, viewFormat: srgbView ?? format, adapter: summarizeAdapter(adapter), lost };
}

function summarizeAdapter(adapter: GPUAdapter): AdapterSummary {
  const info = (adapter as GPUAdapter & { info?: GPUAdapterInfo }).info;
  const fallback = (info as (GPUAdapterInfo & { isFallbackAdapter?: boolean }) | undefined)?.isFallbackAdapter
    ?? (adapter as GPUAdapter & { isFallbackAdapter?: boolean }).isFallbackAdapter
    ?? false;
  return {
    vendor: info?.vendor ?? '',
    architecture: info?.architecture ?? '',
    device: info?.device ?? '',
    description: info?.description ?? '',
    isFallbackAdapter: Boolean(fallback),
  };
}
