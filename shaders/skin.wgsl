// Skin pass (docs/models.md §10): parallax occlusion mapping of the large wrinkles ([T] §7.1.2,
// listing A.1), fine wrinkles in the large wrinkles' tangent frame ([T] §7.2), skin
// micro-relief ([P]) combined by reoriented normal mapping, wrap-lit skin with a
// Fresnel-weighted GGX lobe, ACES-fitted tone mapping.
//
// Two passes: `vs_main` + `fs_surface` rasterise the mesh into a G-buffer (`Surface`),
// `vs_fullscreen` + `fs_shade` shade it. The second alone redraws an age step or a new map.
//
// `Frame` and its binding come from frame.wgsl, and the shared helpers (tone curve, sRGB,
// octahedral packing, cavity) from common.wgsl, both put in front of this file when it is
// loaded (crates/render/src/shaders.rs).


// How far the red light travels under the skin, in relief depths (`disp.x`, 1.7 mm on the
// default head): ≈ 1.5 mm.
const SSS_RADIUS: f32 = 0.9;
// The ring's eight directions, 45° apart from +u (compose.rs `RING`).
const RING: array<vec2<f32>, 8> = array<vec2<f32>, 8>(
    vec2<f32>(1.0, 0.0),
    vec2<f32>(0.70710677, 0.70710677),
    vec2<f32>(0.0, 1.0),
    vec2<f32>(-0.70710677, 0.70710677),
    vec2<f32>(-1.0, 0.0),
    vec2<f32>(-0.70710677, -0.70710677),
    vec2<f32>(0.0, -1.0),
    vec2<f32>(0.70710677, -0.70710677),
);
// How much of the sky and of the light a full hollow of the aged shape loses.
const HOLLOW_AMBIENT: f32 = 0.6;
const HOLLOW_LIGHT: f32 = 0.45;
// Steps of the occlusion ratio per unit in the stored surface (its quantum: 0.5 %).
const OCCLUSION_STEPS: f32 = 200.0;
// The fill light's colour over the key's: a little cooler (a sky-lit bounce).
const FILL_TINT: vec3<f32> = vec3<f32>(0.92, 0.96, 1.0);
// How much less of the light an occlusion takes from the channel that scatters farthest.
const OCCLUSION_TINT: f32 = 0.45;
// How far the red channel's normal leans toward the blurred relief's on light skin (red
// light scatters farther under the skin, so a fold's bottom stays redder than its walls):
// at 1 the MakeHuman heads' forehead lines read, blind, as "red-orange cores, as if drawn
// in marker" (round 7 of docs/ratings.md); at 0 their creases are brown, and the scan's
// barely changes.
const RED_SCATTER: f32 = 0.25;

// How much the hair present over the scalp darkens it (its shadow), per unit of
// `hair.scalp_tint`: a white fringe over pale skin with no shadow under it read, blind, as
// "a flat painted layer".
const HAIR_SHADOW: f32 = 0.35;
const MODE_LINEAR: u32 = 0u;
const MODE_BINARY: u32 = 1u;
const MODE_COMBINED: u32 = 2u;
const MODE_NORMAL_ONLY: u32 = 3u;
const MODE_DISPLACEMENT: u32 = 4u;

// Large wrinkles: height in [0, 1] (1 = the polygon's surface = unwrinkled skin, the
// wrinkles' depth below it = 1 − height; docs/models.md §10), over the mesh UV.
@group(0) @binding(1) var large_map: texture_2d<f32>;
// Tileable micro-relief heights (height units of the project), one tile = map_size_mm.
@group(0) @binding(2) var micro_map: texture_2d<f32>;
// Tileable fine-wrinkle heights.
@group(0) @binding(3) var fine_map: texture_2d<f32>;
// Wraps in u (the head's seam at the back, docs/models.md §1 UV layout), clamps in v.
@group(0) @binding(4) var surface_sampler: sampler;
// Wraps both ways: the tiles repeat over the head.
@group(0) @binding(5) var tile_sampler: sampler;
// The head's base colour map (sRGB texture, read as linear) over the mesh UV, when
// frame.hair_misc.w is 1; a white texel otherwise.
@group(0) @binding(6) var colour_map: texture_2d<f32>;
// The head's own tangent-space normal map (linear) over the mesh UV, when bit 2 of
// frame.hair_misc.w is set; a flat texel otherwise.
@group(0) @binding(7) var head_normal_map: texture_2d<f32>;
// Where the micro-relief lies over the mesh UV (linear; its weight in red, 0–1: the lips'
// red keeps a fifth, docs/models.md §4 "Where on the head"); a white texel when the
// head has none.
@group(0) @binding(8) var micro_weight_map: texture_2d<f32>;

struct VertexIn {
    @location(0) position: vec3<f32>,
    @location(1) normal: vec3<f32>,
    @location(2) uv: vec2<f32>,
    // xyz: tangent (toward +u); w: handedness, bitangent = w·cross(N, T) (toward +v).
    @location(3) tangent: vec4<f32>,
    // The shape of the view's age (docs/models.md §13): the vertex's displacement (mesh
    // units) and its displaced normal (zero: keep `normal`).
    @location(4) shape_delta: vec3<f32>,
    @location(5) shape_normal: vec3<f32>,
    // How hollowed the shape left it, 0–1 (crates/render/src/mesh.rs `hollow_occlusion`).
    @location(6) shape_hollow: f32,
    // How much of the sky it lost to the shape around it: 1 − the occlusion ratio
    // (docs/models.md §13 "Occlusion"; negative for sky gained).
    @location(7) shape_sky_lost: f32,
}

struct VertexOut {
    @builtin(position) clip: vec4<f32>,
    @location(0) world_pos: vec3<f32>,
    @location(1) normal: vec3<f32>,
    @location(2) uv: vec2<f32>,
    @location(3) tangent: vec4<f32>,
    @location(4) hollow: f32,
    @location(5) sky_lost: f32,
}

@vertex
fn vs_main(in: VertexIn) -> VertexOut {
    var p = in.position + in.shape_delta;
    var n = in.normal;
    var t = in.tangent;
    if dot(in.shape_normal, in.shape_normal) > 0.25 {
        // The displaced normal, and the tangent turned with it (Gram–Schmidt: still along
        // +u, so the maps' frame is the one they were baked against, turned).
        n = in.shape_normal;
        t = vec4<f32>(normalize(t.xyz - n * dot(n, t.xyz)), t.w);
    }
    if frame.pom.x == MODE_DISPLACEMENT {
        // [P] eq. 14, P' = P + d(u,v)·n, with the same depth convention as POM: the
        // polygon is the top of the height field (unwrinkled skin), h = 0 lies `disp.y`
        // below it (the bottom of a full-depth wrinkle).
        let h = textureSampleLevel(large_map, surface_sampler, tex(in.uv), 0.0).r;
        p = p + n * ((h - 1.0) * frame.disp.y);
    }
    var out: VertexOut;
    out.clip = frame.clip_from_world * vec4<f32>(p, 1.0);
    out.world_pos = p;
    out.normal = n;
    out.uv = in.uv;
    out.tangent = t;
    out.hollow = in.shape_hollow;
    out.sky_lost = in.shape_sky_lost;
    return out;
}

// docs/models.md §1 UV (v up) → texture coordinates (row 0 of every map is its top, v = 1).
fn tex(uv: vec2<f32>) -> vec2<f32> {
    return vec2<f32>(uv.x, 1.0 - uv.y);
}

fn large_height(uv: vec2<f32>, ddx: vec2<f32>, ddy: vec2<f32>) -> f32 {
    return textureSampleGrad(large_map, surface_sampler, tex(uv), ddx, ddy).r;
}

// The ray at depth `layer` (1 = polygon, 0 = bottom) has moved `shift·(1 − layer)` in UV.
fn ray_uv(uv0: vec2<f32>, shift: vec2<f32>, layer: f32) -> vec2<f32> {
    return uv0 + shift * (1.0 - layer);
}

// Parallax occlusion mapping, docs/models.md §10 / [T] listing A.1. `view_ts` is the unit vector
// toward the eye in tangent space. Returns (uv at the hit, depth layer of the hit).
fn pom(uv0: vec2<f32>, view_ts: vec3<f32>, ddx: vec2<f32>, ddy: vec2<f32>) -> vec3<f32> {
    let mode = frame.pom.x;
    // Clamped so a ray at the silhouette does not shoot across the whole map.
    let shift = -view_ts.xy / max(view_ts.z, 0.08) * frame.disp.x;
    // The interval [lo, hi] of layers holding the first crossing: hi above, lo below.
    var lo = 0.0;
    var hi = 1.0;
    if mode == MODE_LINEAR || mode == MODE_COMBINED {
        let steps = max(frame.pom.y, 1u);
        let step = 1.0 / f32(steps);
        var layer = 1.0;
        var h = large_height(uv0, ddx, ddy);
        var i = 0u;
        // March while the ray is above the height field; h ≥ 0 = layer after L steps,
        // so the loop always ends below (or on) the surface.
        loop {
            if i >= steps || layer <= h {
                break;
            }
            layer = layer - step;
            h = large_height(ray_uv(uv0, shift, layer), ddx, ddy);
            i = i + 1u;
        }
        lo = layer;
        hi = min(layer + step, 1.0);
        if mode == MODE_LINEAR {
            // Linear only: the first step found below the surface, unrefined ([T]).
            return vec3<f32>(ray_uv(uv0, shift, lo), lo);
        }
    }
    // Binary search: B halvings of [lo, hi] (the whole depth in binary-only mode, which
    // is why that mode can settle on a crossing behind the nearest one, [T] §8).
    let halvings = frame.pom.z;
    var j = 0u;
    loop {
        if j >= halvings {
            break;
        }
        let mid = 0.5 * (lo + hi);
        let h = large_height(ray_uv(uv0, shift, mid), ddx, ddy);
        if mid > h {
            hi = mid;
        } else {
            lo = mid;
        }
        j = j + 1u;
    }
    let layer = 0.5 * (lo + hi);
    return vec3<f32>(ray_uv(uv0, shift, layer), layer);
}

// Tangent-space normal of a height texture by central differences (docs/models.md §5:
// n = normalize(−s·∂h/∂u, −s·∂h/∂v, 1), s in UV units per height unit).
fn height_normal(
    map: texture_2d<f32>,
    samp: sampler,
    uv: vec2<f32>,
    strength: f32,
    ddx: vec2<f32>,
    ddy: vec2<f32>,
) -> vec3<f32> {
    let size = vec2<f32>(textureDimensions(map));
    let du = vec2<f32>(1.0 / size.x, 0.0);
    let dv = vec2<f32>(0.0, 1.0 / size.y);
    let hu = textureSampleGrad(map, samp, tex(uv + du), ddx, ddy).r
        - textureSampleGrad(map, samp, tex(uv - du), ddx, ddy).r;
    let hv = textureSampleGrad(map, samp, tex(uv + dv), ddx, ddy).r
        - textureSampleGrad(map, samp, tex(uv - dv), ddx, ddy).r;
    let dh = vec2<f32>(hu * size.x, hv * size.y) * 0.5;
    return normalize(vec3<f32>(-strength * dh, 1.0));
}

// Reoriented normal mapping (Barré-Brisebois & Hill 2012): `detail` rotated by the
// rotation that takes +z to `base`. Adding the vectors would flatten both layers.
fn rnm(base: vec3<f32>, detail: vec3<f32>) -> vec3<f32> {
    let t = base + vec3<f32>(0.0, 0.0, 1.0);
    let u = detail * vec3<f32>(-1.0, -1.0, 1.0);
    return normalize(t * dot(t, u) / t.z - u);
}

// docs/models.md §10 "Fine wrinkles": perturb in the large wrinkles' tangent frame,
// T = normalize(N.z, 0, −N.x), B = normalize(0, N.z, −N.y).
fn in_large_frame(n_large: vec3<f32>, fine: vec3<f32>) -> vec3<f32> {
    let t = normalize(vec3<f32>(n_large.z, 0.0, -n_large.x));
    let b = normalize(vec3<f32>(0.0, n_large.z, -n_large.y));
    return normalize(t * fine.x + b * fine.y + n_large * fine.z);
}

fn output_colour(linear: vec3<f32>) -> vec4<f32> {
    let mapped = aces(linear);
    if frame.camera_pos.w > 0.5 {
        return vec4<f32>(srgb_encode(mapped), 1.0);
    }
    return vec4<f32>(mapped, 1.0);
}

// GGX distribution with Smith-Schlick visibility: a rough, oily dielectric lobe
// (skin: F0 ≈ 0.028, roughness ≈ 0.4, after the d'Eon & Luebke Kelemen/Szirmay-Kalos fit).
fn skin_specular(n: vec3<f32>, v: vec3<f32>, l: vec3<f32>, roughness: f32, f0: f32) -> f32 {
    let h = normalize(v + l);
    let n_l = max(dot(n, l), 0.0);
    let n_v = max(dot(n, v), 1e-3);
    let n_h = max(dot(n, h), 0.0);
    let a2 = roughness * roughness * roughness * roughness;
    let d = a2 / (3.14159265 * pow(n_h * n_h * (a2 - 1.0) + 1.0, 2.0));
    let k = roughness * roughness * 0.5;
    let vis = 1.0 / ((n_l * (1.0 - k) + k) * (n_v * (1.0 - k) + k) * 4.0);
    let fresnel = f0 + (1.0 - f0) * pow(1.0 - max(dot(h, v), 0.0), 5.0);
    return d * vis * fresnel * n_l;
}

// What the skin's shading needs of the surface at one pixel: everything but the age, the
// maps and the light. The surface pass stores it per pixel (`fs_surface`); the shading
// pass (`fs_shade`) reads it back, so a frame whose view did not move (an age step, a
// re-baked map) shades the stored surface without rasterising the mesh again.
struct Surface {
    uv: vec2<f32>,
    // Screen-space derivatives of uv, taken while rasterising (for the samples' mips).
    ddx: vec2<f32>,
    ddy: vec2<f32>,
    // The geometric frame: unit normal, unit tangent (Gram-Schmidt), bitangent sign.
    n: vec3<f32>,
    t: vec3<f32>,
    b_sign: f32,
    // Unit vector toward the eye.
    to_eye: vec3<f32>,
    // How hollowed the aged shape left the skin here, 0–1.
    hollow: f32,
    // The sky it sees over the sky it saw undisplaced (docs/models.md §13 "Occlusion").
    occlusion: f32,
    // How much of the key light reaches it past the surface in view (1: all of it).
    key_light: f32,
}

// The surface in three targets (32 bytes, the smallest per-sample limit wgpu allows):
// uv in f32, since POM marches it; the derivatives and the frame in f16. The hollow and
// the occlusion ride on the bitangent sign: ±(1 + hollow + 2·k), the hollow in [0, 1) and
// k the occlusion ratio in steps of 1/OCCLUSION_STEPS (an integer of at most 9 bits: an
// f32 keeps the hollow to 2⁻¹⁴ beside it). The direction to
// the eye is not stored: the shading pass has it from the pixel's view ray. The depth is
// kept too (in [0, 1]; the renderer clears it to 2, the background), so a frame can
// restore the depth buffer from it without copying a depth texture.
struct SurfaceOut {
    // uv, bitangent sign × (1 + hollow + 2·occlusion steps), depth.
    @location(0) s0: vec4<f32>,
    // dpdx(uv), dpdy(uv).
    @location(1) s1: vec4<f32>,
    // Octahedral normal, octahedral tangent.
    @location(2) s2: vec4<f32>,
}

@fragment
fn fs_surface(in: VertexOut) -> SurfaceOut {
    let n = normalize(in.normal);
    // Gram-Schmidt: interpolation bends the tangent away from the normal.
    let t = normalize(in.tangent.xyz - n * dot(n, in.tangent.xyz));
    var out: SurfaceOut;
    let hollow = clamp(in.hollow, 0.0, 0.999);
    let occlusion = round(clamp(1.0 - in.sky_lost, 0.0, 2.0) * OCCLUSION_STEPS);
    let packed = 1.0 + hollow + 2.0 * occlusion;
    out.s0 = vec4<f32>(in.uv, select(-1.0, 1.0, in.tangent.w >= 0.0) * packed, in.clip.z);
    out.s1 = vec4<f32>(dpdx(in.uv), dpdy(in.uv));
    out.s2 = vec4<f32>(oct_encode(n), oct_encode(t));
    return out;
}

// The stored surface: the surface pass's three targets.
@group(1) @binding(0) var surface0: texture_2d<f32>;
@group(1) @binding(1) var surface1: texture_2d<f32>;
@group(1) @binding(2) var surface2: texture_2d<f32>;

// One triangle covering the target (vertices 0, 1, 2).
@vertex
fn vs_fullscreen(@builtin(vertex_index) i: u32) -> @builtin(position) vec4<f32> {
    let x = f32((i << 1u) & 2u) * 2.0 - 1.0;
    let y = f32(i & 2u) * 2.0 - 1.0;
    return vec4<f32>(x, y, 0.0, 1.0);
}

@fragment
fn fs_shade(@builtin(position) pos: vec4<f32>) -> @location(0) vec4<f32> {
    let p = vec2<i32>(pos.xy);
    let s0 = textureLoad(surface0, p, 0);
    if s0.w > 1.5 {
        // Background: the pass cleared it.
        discard;
    }
    let s1 = textureLoad(surface1, p, 0);
    let s2 = textureLoad(surface2, p, 0);
    // The pixel centre's view ray: the surface point seen there lies on it, so the
    // direction to the eye is the ray's, reversed (the camera is a perspective one).
    let size = vec2<f32>(frame.hair_misc.x, frame.layers.w);
    let ndc = vec2<f32>(2.0 * pos.x / size.x - 1.0, 1.0 - 2.0 * pos.y / size.y);
    let on_ray = frame.world_from_clip * vec4<f32>(ndc, 0.5, 1.0);
    var s: Surface;
    s.uv = s0.xy;
    s.ddx = s1.xy;
    s.ddy = s1.zw;
    s.n = oct_decode(s2.xy);
    s.t = oct_decode(s2.zw);
    s.b_sign = sign(s0.z);
    let packed = abs(s0.z) - 1.0;
    let steps = floor(packed * 0.5);
    s.hollow = packed - 2.0 * steps;
    s.occlusion = steps / OCCLUSION_STEPS;
    s.to_eye = normalize(frame.camera_pos.xyz - on_ray.xyz / on_ray.w);
    s.key_light = key_shadow(pos.xy, size, ndc, s0.w, s.n);
    return shade(s);
}

// The contact shadows' rays (toward points spread over the light, so the shadow's edge is
// soft: a face lit by a window, not the sun), the steps along each, and how far the first
// step starts (of the reach).
const SHADOW_RAYS: u32 = 4u;
const SHADOW_STEPS: u32 = 8u;
const SHADOW_START: f32 = 0.02;
// The light's angular radius seen from the skin, radians.
const SHADOW_SPREAD: f32 = 0.12;
// How much of the key light a point every ray finds blocked still gets (the skin's own
// scattering and the penumbra's floor).
const SHADOW_FLOOR: f32 = 0.15;
// How much nearer than a ray's point the surface must be, per unit of the ray's length,
// to block it.
const SHADOW_BIAS: f32 = 0.1;
// Over what n·l past the terminator the shadows fade in.
const SHADOW_TERMINATOR: f32 = 0.3;

// The world position seen at a pixel's NDC with the stored depth `depth`.
fn world_at(ndc: vec2<f32>, depth: f32) -> vec3<f32> {
    let p = frame.world_from_clip * vec4<f32>(ndc, depth, 1.0);
    return p.xyz / p.w;
}

// Interleaved gradient noise (Jimenez 2014) at a pixel, in [0, 1).
fn ign(px: vec2<f32>) -> f32 {
    return fract(52.9829189 * fract(dot(px, vec2<f32>(0.06711056, 0.00583715))));
}

// Whether the ray from `p` along `dir` meets the stored surface within `reach`.
fn shadow_ray(p: vec3<f32>, dir: vec3<f32>, n: vec3<f32>, size: vec2<f32>, reach: f32, jitter: f32) -> bool {
    let eye = frame.camera_pos.xyz;
    for (var i = 0u; i < SHADOW_STEPS; i = i + 1u) {
        let f = (f32(i) + jitter) / f32(SHADOW_STEPS);
        // Denser near the point: the small occluders (a fold, the lid's rim) are close.
        let along = reach * mix(SHADOW_START, 1.0, f * f);
        let q = p + dir * along + n * (0.02 * along);
        let c = frame.clip_from_world * vec4<f32>(q, 1.0);
        if c.w <= 0.0 {
            return false;
        }
        let q_ndc = c.xy / c.w;
        let q_px = vec2<f32>(0.5 * (q_ndc.x + 1.0) * size.x, 0.5 * (1.0 - q_ndc.y) * size.y);
        if any(q_px < vec2<f32>(0.0)) || any(q_px >= size) {
            return false;
        }
        let seen_depth = textureLoad(surface0, vec2<i32>(q_px), 0).w;
        if seen_depth > 1.5 {
            // Background: nothing there.
            continue;
        }
        // Distances from the eye: the surface seen there against the ray's point.
        let in_front = distance(q, eye) - distance(world_at(q_ndc, seen_depth), eye);
        // Nearer than the ray by more than a share of the way it has come: on a convex
        // surface seen obliquely the skin just beside the point lies a little in front of
        // the ray and is no occluder.
        if in_front > SHADOW_BIAS * along && in_front < frame.shadow.y {
            return true;
        }
    }
    return false;
}

// Contact shadows of the key light (docs/models.md §10 "Shadows"): from the surface point
// seen at this pixel, rays toward the light are marched through the stored surface; where
// the surface seen along one lies in front of it (nearer the eye) by less than an
// occluder's thickness, that ray is blocked. Only what is in view casts, and only within
// `frame.shadow.x`: the nose on the cheek, the brow over the lid, the cheek over its fold,
// the jaw on the neck.
fn key_shadow(px: vec2<f32>, size: vec2<f32>, ndc: vec2<f32>, depth: f32, n: vec3<f32>) -> f32 {
    let reach = frame.shadow.x;
    let l = frame.light_dir.xyz;
    if reach <= 0.0 || dot(n, l) <= 0.0 {
        return 1.0;
    }
    let p = world_at(ndc, depth);
    // Two axes across the light, turned per pixel so the rays' offsets differ from pixel
    // to pixel (equal steps and offsets everywhere drew the shadow's edge as stripes and
    // the mesh's facets; they average out over the supersampled pixel).
    // (Any axis well off the light: up, unless the light is nearly overhead.)
    let helper = select(vec3<f32>(1.0, 0.0, 0.0), vec3<f32>(0.0, 1.0, 0.0), abs(l.y) < 0.9);
    let a = normalize(cross(l, helper));
    let b = cross(l, a);
    let turn = 6.2831853 * ign(px);
    let ca = cos(turn);
    let sa = sin(turn);
    let jitter = ign(px + vec2<f32>(17.0, 31.0));
    var blocked = 0.0;
    for (var k = 0u; k < SHADOW_RAYS; k = k + 1u) {
        // Points over the light's disc: a ring of SHADOW_RAYS at 0.7 of its radius.
        let phi = 6.2831853 * f32(k) / f32(SHADOW_RAYS);
        let o = vec2<f32>(cos(phi) * ca - sin(phi) * sa, sin(phi) * ca + cos(phi) * sa) * (0.7 * SHADOW_SPREAD);
        let dir = normalize(l + a * o.x + b * o.y);
        if shadow_ray(p, dir, n, size, reach, fract(jitter + 0.25 * f32(k))) {
            blocked = blocked + 1.0;
        }
    }
    // Faded out toward the terminator, where the light grazes the skin and the wrap
    // lighting carries on past it unshadowed (a shadow ending at n·l = 0 drew streaks
    // along a low-poly head's cheek).
    let shadow = (1.0 - SHADOW_FLOOR) * blocked / f32(SHADOW_RAYS);
    return 1.0 - shadow * smoothstep(0.0, SHADOW_TERMINATOR, dot(n, l));
}

// The skin's depth from the stored surface, into a depth buffer cleared to 1: the hair and
// the wireframe are then tested against the skin (the wireframe writes its own depth,
// blended hair none) without touching the stored surface.
@fragment
fn fs_depth(@builtin(position) pos: vec4<f32>) -> @builtin(frag_depth) f32 {
    let s0 = textureLoad(surface0, vec2<i32>(pos.xy), 0);
    if s0.w > 1.5 {
        discard;
    }
    return s0.w;
}

// Wrap diffuse per channel, D = clamp((n·l + w) / (1 + w)², 0, 1) (docs/models.md §10).
fn wrap_diffuse(n_l: f32, wrap: vec3<f32>) -> vec3<f32> {
    return wrap_diffuse3(vec3<f32>(n_l), wrap);
}

// The same with each channel's own n·l (its own normal: see SSS_RADIUS).
fn wrap_diffuse3(n_l: vec3<f32>, wrap: vec3<f32>) -> vec3<f32> {
    return clamp((n_l + wrap) / ((1.0 + wrap) * (1.0 + wrap)), vec3<f32>(0.0), vec3<f32>(1.0));
}

// The large wrinkles' normal from the slope between points `r` UV units to each side: the
// relief averaged over about 2r (the red channel's, docs/models.md §10 "Subsurface").
fn wide_normal(uv: vec2<f32>, r: f32, strength: f32, ddx: vec2<f32>, ddy: vec2<f32>) -> vec3<f32> {
    // No relief (the depth slider at 0 makes r 0): flat. (0 / 0 here lit the red channel
    // by a NaN normal, and the whole head turned cyan.)
    if r <= 0.0 {
        return vec3<f32>(0.0, 0.0, 1.0);
    }
    let du = vec2<f32>(r, 0.0);
    let dv = vec2<f32>(0.0, r);
    let hu = large_height(uv + du, ddx, ddy) - large_height(uv - du, ddx, ddy);
    let hv = large_height(uv + dv, ddx, ddy) - large_height(uv - dv, ddx, ddy);
    return normalize(vec3<f32>(-strength * vec2<f32>(hu, hv) / (2.0 * r), 1.0));
}

// How much of each channel an occlusion takes (1 = all of it): red least, in proportion to
// how far the skin's wrap lighting carries it (docs/models.md §10 "Occlusion tint").
fn occlusion_tint() -> vec3<f32> {
    let w = frame.skin_wrap.rgb / max(max(frame.skin_wrap.r, max(frame.skin_wrap.g, frame.skin_wrap.b)), 1e-3);
    return vec3<f32>(1.0) - OCCLUSION_TINT * w;
}

// The skin's colour at a surface point (docs/models.md §10).
fn shade(s: Surface) -> vec4<f32> {
    let ddx = s.ddx;
    let ddy = s.ddy;
    let micro_uv0 = s.uv * frame.tiling.xy;
    let fine_uv0 = s.uv * frame.tiling.zw;
    let ddx_micro = ddx * frame.tiling.xy;
    let ddy_micro = ddy * frame.tiling.xy;
    let ddx_fine = ddx * frame.tiling.zw;
    let ddy_fine = ddy * frame.tiling.zw;

    let n_geo = s.n;
    let t_geo = s.t;
    let b_geo = cross(n_geo, t_geo) * s.b_sign;
    let to_eye = s.to_eye;
    let view_ts = vec3<f32>(dot(to_eye, t_geo), dot(to_eye, b_geo), dot(to_eye, n_geo));

    let mode = frame.pom.x;
    var uv = s.uv;
    if mode <= MODE_COMBINED {
        uv = pom(s.uv, view_ts, ddx, ddy).xy;
    }
    if frame.hair_misc.z > 0.5 && frame.hair_misc.z < 1.5 {
        return vec4<f32>(uv, s.uv);
    }
    // The micro-relief and fine tiles move with the POM offset: they lie on the surface.
    let offset = uv - s.uv;

    // Large-wrinkle normal from the heights at the hit, with the slope the march used.
    let n_large = height_normal(large_map, surface_sampler, uv, frame.disp.x, ddx, ddy);
    let n_fine_tile = height_normal(fine_map, tile_sampler, fine_uv0 + offset * frame.tiling.zw, frame.layers.y, ddx_fine, ddy_fine);
    let fine = in_large_frame(n_large, n_fine_tile);
    // docs/models.md §10: the age blends linearly from the surface normal to the fine-wrinkle one.
    var n_ts = normalize(mix(n_large, fine, clamp(frame.disp.z, 0.0, 1.0)));
    if frame.layers.z > 0.5 {
        let micro_weight = textureSampleGrad(micro_weight_map, surface_sampler, tex(uv), ddx, ddy).r;
        let n_micro = height_normal(micro_map, tile_sampler, micro_uv0 + offset * frame.tiling.xy, frame.layers.x * micro_weight, ddx_micro, ddy_micro);
        n_ts = rnm(n_ts, n_micro);
    }
    // The light that enters the skin leaves it up to millimetres away, red farthest
    // (docs/models.md §10 "Subsurface"): red is lit half by the full relief and half by
    // the large wrinkles' relief averaged over SSS_RADIUS relief depths around the point
    // (none of the finer layers); green and blue by the full relief.
    var n_soft_ts = wide_normal(uv, SSS_RADIUS * frame.disp.x, frame.disp.x, ddx, ddy);
    let head_maps = u32(frame.hair_misc.w);
    if (head_maps & 2u) != 0u {
        // The head's own relief is the base the layers lie on.
        var n_head = textureSampleGrad(head_normal_map, surface_sampler, tex(uv), ddx, ddy).rgb * 2.0 - vec3<f32>(1.0);
        if (head_maps & 4u) != 0u {
            n_head.y = -n_head.y;
        }
        n_ts = rnm(normalize(n_head), n_ts);
        n_soft_ts = rnm(normalize(n_head), n_soft_ts);
    }
    if frame.hair_misc.z > 1.5 {
        return vec4<f32>(n_ts, 1.0);
    }
    let n = normalize(t_geo * n_ts.x + b_geo * n_ts.y + n_geo * n_ts.z);
    // Melanin absorbs the red that scatters back out of a fold: on dark skin red is lit
    // by the full relief too (the red's wrap over the blue's, which the frame narrows for
    // dark skin, `view::wrap_for_skin`, measures how far red scatters: 1 on light skin).
    // Lit half by the blurred relief on dark skin, every fold drew a red line.
    let red_scatter = RED_SCATTER * clamp((frame.skin_wrap.r / max(frame.skin_wrap.b, 1e-3) - 1.0) / 1.1, 0.0, 1.0);
    let n_red = normalize(n + red_scatter * (t_geo * n_soft_ts.x + b_geo * n_soft_ts.y + n_geo * n_soft_ts.z));

    // The albedo arrives with the age's paling applied (docs/models.md "Age"); a head's
    // own colour map pales the same way.
    var albedo = frame.skin_albedo.rgb;
    if (head_maps & 1u) != 0u {
        let c = textureSampleGrad(colour_map, surface_sampler, tex(uv), ddx, ddy);
        albedo = mix(c.rgb, frame.skin_spec.yzw, clamp(frame.skin_albedo.w, 0.0, 1.0));
        // The scalp under the hair present at this age takes the hair's colour (the roots
        // of short hair; docs/models.md §9 "The scalp under the hair"): the alpha is the
        // texel's hair disappearance age a (1 + 254·a over 255; 0 where none ever grows).
        if frame.scalp.x > 0.0 {
            let byte = c.a * 255.0;
            let a = (byte - 1.0) / 254.0;
            let t = frame.disp.w;
            // Present while a ≥ t; fading where it will soon go (the ragged fringe thins)
            // and where the blurred age falls toward the edge of the hair.
            let present = smoothstep(t - 0.05, t + 0.05, a) * smoothstep(t, t + 0.5, a)
                * smoothstep(0.3, 1.0, byte);
            let hair = mix(frame.hair_base.rgb, frame.hair_gray.rgb, frame.scalp.y);
            // Pigmented roots darken the scalp; gray ones barely show on it (a white scalp
            // under a white fringe read, blind, as a painted band with a hard edge).
            let roots = 1.0 - 0.75 * frame.scalp.y;
            albedo = mix(albedo, hair, frame.scalp.x * present * roots);
            // The strands' shadow on it, whatever their colour.
            albedo *= 1.0 - HAIR_SHADOW * frame.scalp.x * present;
        }
    }

    let l = frame.light_dir.xyz;
    let light = frame.light_colour.rgb * frame.light_dir.w;
    // Wrap lighting per channel: red light scatters farthest under the skin, so its
    // terminator wraps widest (GPU Gems 1 ch. 16, a cheap stand-in for [P]'s SSS).
    let wrap = frame.skin_wrap.rgb;
    // Light lost in a fold or a shadow is partly given back under the skin, red most (it
    // scatters farthest): each loss is scaled per channel, red least.
    let keep = occlusion_tint();
    // The key's contact shadow takes its light.
    let key = vec3<f32>(1.0) - (1.0 - s.key_light) * keep;
    let diffuse = key * wrap_diffuse3(vec3<f32>(dot(n_red, l), dot(n, l), dot(n, l)), wrap);
    // Hemisphere ambient through the perturbed normal, so micro-relief shows in shadow.
    let sky = 0.6 + 0.4 * n.y;
    // Cavity occlusion (docs/models.md §10): the bottom of a crease sees less of the sky
    // and of the light than the skin around it. How much deeper the map is at the hit than
    // on a ring CAVITY_RING relief depths around it (a narrow crease: its whole depth; a
    // wide hollow or a fold's wall: little), scaled by the drawn relief (0 with none).
    let depth01 = clamp(1.0 - large_height(uv, ddx, ddy), 0.0, 1.0);
    var ring = 0.0;
    for (var i = 0; i < 8; i++) {
        let at = uv + CAVITY_RING * frame.disp.x * RING[i];
        ring += clamp(1.0 - large_height(at, ddx, ddy), 0.0, 1.0);
    }
    let local = max(depth01 - ring / 8.0, 0.0);
    let cavity_loss = cavity_loss(local, frame.disp.x);
    // A crease's floor is rougher than the open skin (the GLB's roughness texture too).
    let roughness = crease_roughness(frame.skin_wrap.w, cavity_loss);
    let spec = s.key_light * skin_specular(n, to_eye, l, roughness, frame.skin_spec.x);
    // A hollow of the aged shape (temples, tear trough, below the cheekbone) sees less of
    // the sky and of the light (docs/models.md §13 "Hollows").
    let hollow = clamp(s.hollow, 0.0, 1.0);
    let cavity = vec3<f32>(1.0) - cavity_loss * keep;
    let ambient = frame.light_colour.w * sky * cavity * (vec3<f32>(1.0) - HOLLOW_AMBIENT * hollow * keep);
    let direct = cavity * (vec3<f32>(1.0) - HOLLOW_LIGHT * hollow * keep);
    // What the aged shape hides of the sky that the skin saw undisplaced (the scan's colour
    // holds the rest's occlusion): the whole of the skin's light times the ratio.
    let occlusion = vec3<f32>(1.0) - (1.0 - s.occlusion) * keep;
    // The fill light: a large soft source on the other side (diffuse only), a little
    // cooler than the key, so the side away from the key keeps its shape.
    let f = frame.fill_dir.xyz;
    let fill = wrap_diffuse3(vec3<f32>(dot(n_red, f), dot(n, f), dot(n, f)), wrap) * frame.light_colour.rgb
        * frame.fill_dir.w * FILL_TINT;
    let colour = (albedo * ((diffuse * light + fill) * direct + ambient)
        + vec3<f32>(spec) * light * cavity) * occlusion;
    return output_colour(colour);
}

// Wireframe overlay: the mesh's edges drawn as lines over the skin (same vertex stage), a
// flat colour encoded like the skin's output.
@fragment
fn fs_wire(in: VertexOut) -> @location(0) vec4<f32> {
    let c = vec3<f32>(0.25, 0.85, 1.0);
    if frame.camera_pos.w > 0.5 {
        return vec4<f32>(pow(c, vec3<f32>(1.0 / 2.2)), 1.0);
    }
    return vec4<f32>(c, 1.0);
}
