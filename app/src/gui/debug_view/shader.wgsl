// The debug view's three pipelines: shaded meshes, screen-space-wide line
// segments (both into an offscreen multisampled target with depth), and a
// blit of the resolved target into egui's render pass.

struct Uniforms {
    view_proj: mat4x4<f32>,
    // Target size in physical pixels.
    viewport: vec2<f32>,
    // Physical pixels per egui point (line widths are given in points).
    pixels_per_point: f32,
    _pad: f32,
    // Unit vector toward the headlight, in the world.
    light: vec4<f32>,
};

@group(0) @binding(0) var<uniform> u: Uniforms;

fn linear_to_srgb(c: vec3<f32>) -> vec3<f32> {
    let lo = c * 12.92;
    let hi = 1.055 * pow(c, vec3<f32>(1.0 / 2.4)) - 0.055;
    return select(hi, lo, c <= vec3<f32>(0.0031308));
}

struct MeshOut {
    @builtin(position) clip: vec4<f32>,
    @location(0) normal: vec3<f32>,
    @location(1) color: vec3<f32>,
};

@vertex
fn mesh_vs(@location(0) position: vec3<f32>, @location(1) normal: vec3<f32>, @location(2) color: vec3<f32>) -> MeshOut {
    var out: MeshOut;
    out.clip = u.view_proj * vec4<f32>(position, 1.0);
    out.normal = normal;
    out.color = color;
    return out;
}

@fragment
fn mesh_fs(in: MeshOut) -> @location(0) vec4<f32> {
    // Two-sided headlight shading: the side facing the observer is lit.
    let n = normalize(in.normal);
    let lambert = abs(dot(n, u.light.xyz));
    let shade = 0.25 + 0.75 * lambert;
    return vec4<f32>(linear_to_srgb(in.color * shade), 1.0);
}

struct LineOut {
    @builtin(position) clip: vec4<f32>,
    @location(0) color: vec4<f32>,
};

// Each instance is one segment a → b drawn as a quad `width` points wide.
@vertex
fn line_vs(
    @builtin(vertex_index) corner: u32,
    @location(0) a: vec3<f32>,
    @location(1) b: vec3<f32>,
    @location(2) color: vec4<f32>,
    @location(3) width: f32,
) -> LineOut {
    var ca = u.view_proj * vec4<f32>(a, 1.0);
    var cb = u.view_proj * vec4<f32>(b, 1.0);
    // Clip the segment against the near plane (z = 0 in wgpu's clip space)
    // so that a segment passing behind the observer still draws its visible part.
    if ca.z < 0.0 && cb.z >= 0.0 {
        ca = mix(ca, cb, ca.z / (ca.z - cb.z));
    } else if cb.z < 0.0 && ca.z >= 0.0 {
        cb = mix(cb, ca, cb.z / (cb.z - ca.z));
    }
    let sa = ca.xy / ca.w * u.viewport * 0.5;
    let sb = cb.xy / cb.w * u.viewport * 0.5;
    var dir = sb - sa;
    if length(dir) < 1e-6 {
        dir = vec2<f32>(1.0, 0.0);
    }
    let side = normalize(vec2<f32>(-dir.y, dir.x)) * 0.5 * width * u.pixels_per_point;
    // Two triangles: corners 0..5 → (end, side).
    let ends = array<f32, 6>(0.0, 1.0, 1.0, 0.0, 1.0, 0.0);
    let sides = array<f32, 6>(-1.0, -1.0, 1.0, -1.0, 1.0, 1.0);
    let end = ends[corner];
    var clip = mix(ca, cb, end);
    let offset = side * sides[corner] / (u.viewport * 0.5) * clip.w;
    clip = vec4<f32>(clip.xy + offset, clip.z, clip.w);
    // A small bias toward the observer keeps lines on a surface visible.
    clip.z = clip.z - 2e-4 * clip.w;
    var out: LineOut;
    out.clip = clip;
    out.color = color;
    if ca.z < 0.0 && cb.z < 0.0 {
        out.clip = vec4<f32>(0.0, 0.0, -1.0, 1.0);
    }
    return out;
}

@fragment
fn line_fs(in: LineOut) -> @location(0) vec4<f32> {
    return in.color;
}

struct BlitOut {
    @builtin(position) clip: vec4<f32>,
    @location(0) uv: vec2<f32>,
};

@vertex
fn blit_vs(@builtin(vertex_index) k: u32) -> BlitOut {
    // One triangle covering the viewport.
    let x = f32((k << 1u) & 2u);
    let y = f32(k & 2u);
    var out: BlitOut;
    out.clip = vec4<f32>(x * 2.0 - 1.0, 1.0 - y * 2.0, 0.0, 1.0);
    out.uv = vec2<f32>(x, y);
    return out;
}

// Bindings 1 and 2: binding 0 is the other pipelines' uniforms.
@group(0) @binding(1) var picture: texture_2d<f32>;
@group(0) @binding(2) var picture_sampler: sampler;

@fragment
fn blit_fs(in: BlitOut) -> @location(0) vec4<f32> {
    return textureSample(picture, picture_sampler, in.uv);
}
