// Blit: a texture onto the bound viewport, as it is (no blending, no colour change). The
// editor shows the 3D view's colour target with it: on a CPU rasteriser a plain textured
// triangle is much cheaper per pixel than egui's image shader.

// The texture holds sRGB-encoded values and the target encodes on write (an sRGB
// format): decode first, so the values land unchanged.
override DECODE_SRGB: bool = false;

@group(0) @binding(0) var source: texture_2d<f32>;
@group(0) @binding(1) var source_sampler: sampler;

struct VertexOut {
    @builtin(position) clip: vec4<f32>,
    @location(0) uv: vec2<f32>,
}

// One triangle covering the viewport (vertices 0, 1, 2); uv (0, 0) at the top left.
@vertex
fn vs_main(@builtin(vertex_index) i: u32) -> VertexOut {
    let uv = vec2<f32>(f32((i << 1u) & 2u), f32(i & 2u));
    var out: VertexOut;
    out.clip = vec4<f32>(uv.x * 2.0 - 1.0, 1.0 - uv.y * 2.0, 0.0, 1.0);
    out.uv = uv;
    return out;
}

@fragment
fn fs_main(in: VertexOut) -> @location(0) vec4<f32> {
    let c = textureSample(source, source_sampler, in.uv);
    if DECODE_SRGB {
        let lo = c.rgb / 12.92;
        let hi = pow((c.rgb + 0.055) / 1.055, vec3<f32>(2.4));
        return vec4<f32>(select(hi, lo, c.rgb <= vec3<f32>(0.04045)), c.a);
    }
    return c;
}

// Over: a second texture laid over the first (the editor's map view: a map picture with
// its UV layout over it), both premultiplied and sRGB-encoded as egui's pictures are,
// composited as egui's blending would, in one unblended pass.
@group(0) @binding(2) var overlay: texture_2d<f32>;

@fragment
fn fs_over(in: VertexOut) -> @location(0) vec4<f32> {
    let base = textureSample(source, source_sampler, in.uv);
    let over = textureSample(overlay, source_sampler, in.uv);
    let c = over.rgb + base.rgb * (1.0 - over.a);
    if DECODE_SRGB {
        let lo = c / 12.92;
        let hi = pow((c + 0.055) / 1.055, vec3<f32>(2.4));
        return vec4<f32>(select(hi, lo, c <= vec3<f32>(0.04045)), 1.0);
    }
    return vec4<f32>(c, 1.0);
}
