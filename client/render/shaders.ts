// The renderer's single WGSL program: instanced meshes lit by one directional light plus a sky/ground ambient term,
// with per-instance flags for the ground grid, sensor outlines and hatching, and distance fog.

/** Bytes per vertex: position (3 floats) + normal (3 floats). */
export const VERTEX_STRIDE_BYTES = 24;
/** Floats per instance: position+flags, rotation quaternion, scale+emissive, colour+alpha. */
export const INSTANCE_FLOATS = 16;
/** Bytes per instance. */
export const INSTANCE_STRIDE_BYTES = INSTANCE_FLOATS * 4;
/** Floats in the per-frame uniform block. */
export const FRAME_UNIFORM_FLOATS = 44;

/** Per-instance flag bits (stored as a float in the instance's position.w). */
export const InstanceFlag = {
  /** Draw the world-space ground grid on upward-facing surfaces. */
  Grid: 1,
  /** Draw only the edges of a box (unit-cube local coordinates), e.g. a trigger zone. */
  Outline: 2,
  /** Draw horizontal stripes only (a see-through volume of any shape). */
  Hatch: 4,
} as const;

/** The WGSL source of the one pipeline. Colours are lit in linear space; ENCODE_SRGB is set when the render target
 * does not encode gamma itself. */
export const SCENE_SHADER_WGSL = /* wgsl */ `
override ENCODE_SRGB: bool = false;

struct Frame {
  viewProj: mat4x4f,
  cameraPos: vec4f,
  lightDir: vec4f,     // direction the light travels (unit)
  lightColor: vec4f,
  skyColor: vec4f,
  groundColor: vec4f,
  fogColor: vec4f,     // linear rgb, w = fog density per metre
  grid: vec4f,         // x = cell size (m), y = major line every N cells, z = outline width (m)
}
@group(0) @binding(0) var<uniform> frame: Frame;

struct VsIn {
  @location(0) position: vec3f,
  @location(1) normal: vec3f,
  @location(2) posFlags: vec4f,
  @location(3) rotation: vec4f,
  @location(4) scaleEmissive: vec4f,
  @location(5) color: vec4f,
}

struct VsOut {
  @builtin(position) clip: vec4f,
  @location(0) world: vec3f,
  @location(1) normal: vec3f,
  @location(2) color: vec3f,
  @location(3) local: vec3f,
  @location(4) @interpolate(flat) flags: u32,
  @location(5) @interpolate(flat) emissive: f32,
  @location(6) @interpolate(flat) scale: vec3f,
}

// The sRGB transfer functions (what an -srgb render target applies in hardware).
fn srgbToLinear(c: vec3f) -> vec3f {
  return select(pow((c + 0.055) / 1.055, vec3f(2.4)), c / 12.92, c <= vec3f(0.04045));
}
fn linearToSrgb(c: vec3f) -> vec3f {
  return select(1.055 * pow(c, vec3f(1.0 / 2.4)) - 0.055, c * 12.92, c <= vec3f(0.0031308));
}

fn rotate(q: vec4f, v: vec3f) -> vec3f {
  let t = 2.0 * cross(q.xyz, v);
  return v + q.w * t + cross(q.xyz, t);
}

@vertex
fn vsMain(in: VsIn) -> VsOut {
  var out: VsOut;
  let scale = in.scaleEmissive.xyz;
  let world = rotate(in.rotation, in.position * scale) + in.posFlags.xyz;
  out.clip = frame.viewProj * vec4f(world, 1.0);
  out.world = world;
  out.normal = rotate(in.rotation, normalize(in.normal / scale));
  // Colours arrive as display (sRGB-like) values: decode once per vertex, light in linear space.
  out.color = srgbToLinear(in.color.rgb);
  out.local = in.position;
  out.flags = u32(in.posFlags.w + 0.5);
  out.emissive = in.scaleEmissive.w;
  out.scale = scale;
  return out;
}

fn gridLine(coord: vec2f) -> f32 {
  let w = max(fwidth(coord), vec2f(1e-6));
  let d = abs(fract(coord - 0.5) - 0.5) / w;
  return 1.0 - min(min(d.x, d.y), 1.0);
}

@fragment
fn fsMain(in: VsOut, @builtin(front_facing) front: bool) -> @location(0) vec4f {
  // Derivatives first, while control flow is still uniform.
  let cell = in.world.xz / frame.grid.x;
  let minor = gridLine(cell);
  let major = gridLine(cell / frame.grid.y);

  if ((in.flags & 2u) != 0u) {
    let a = abs(in.local);
    let width = vec3f(frame.grid.z) / max(in.scale, vec3f(1e-3));
    let near = step(vec3f(1.0) - width, a);
    if (near.x + near.y + near.z < 2.0) { discard; }
  }
  if ((in.flags & 4u) != 0u && fract(in.world.y * 4.0) > 0.35) { discard; }

  var n = normalize(in.normal);
  if (!front) { n = -n; }
  let base = in.color;
  let diffuse = max(dot(n, -frame.lightDir.xyz), 0.0);
  let ambient = mix(frame.groundColor.rgb, frame.skyColor.rgb, n.y * 0.5 + 0.5);
  var lit = base * (ambient + diffuse * frame.lightColor.rgb) + base * in.emissive;
  if ((in.flags & 1u) != 0u && n.y > 0.7) {
    lit = mix(lit, lit * 0.55, minor * 0.6);
    lit = mix(lit, lit * 0.35, major);
  }
  let dist = distance(in.world, frame.cameraPos.xyz);
  let fog = 1.0 - exp(-dist * frame.fogColor.w);
  let color = mix(lit, frame.fogColor.rgb, clamp(fog, 0.0, 1.0));
  if (ENCODE_SRGB) { return vec4f(linearToSrgb(clamp(color, vec3f(0.0), vec3f(1.0))), 1.0); }
  return vec4f(color, 1.0);
}
`;
