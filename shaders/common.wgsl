// Helpers shared by skin.wgsl and hair.wgsl, each written once (crates/render/src/shaders.rs
// puts this file, after frame.wgsl, in front of both). No bindings: a test wraps it in a
// compute shader and compares each helper with its CPU twin in agesim-core
// (crates/render/tests/twins.rs).

// Narkowicz's fit of the ACES filmic curve.
fn aces(x: vec3<f32>) -> vec3<f32> {
    return clamp((x * (2.51 * x + 0.03)) / (x * (2.43 * x + 0.59) + 0.14), vec3<f32>(0.0), vec3<f32>(1.0));
}

// Linear light to the sRGB transfer curve.
fn srgb_encode(c: vec3<f32>) -> vec3<f32> {
    let lo = c * 12.92;
    let hi = 1.055 * pow(c, vec3<f32>(1.0 / 2.4)) - 0.055;
    return select(hi, lo, c <= vec3<f32>(0.0031308));
}

// Octahedral encoding of a unit vector (Cigolle et al. 2014), two numbers in [−1, 1]: the
// G-buffer's normal and tangent; the hair's root direction is packed the same way on the
// CPU (`agesim_core::layers::hair::oct_encode`, as snorm16).
fn oct_encode(n: vec3<f32>) -> vec2<f32> {
    let p = n.xy / (abs(n.x) + abs(n.y) + abs(n.z));
    if n.z >= 0.0 {
        return p;
    }
    return (1.0 - abs(p.yx)) * select(vec2<f32>(-1.0), vec2<f32>(1.0), p >= vec2<f32>(0.0));
}

// Its inverse: the lower hemisphere folded back, x' = x − sign(x)·max(−z, 0), which is
// (1 − |y|)·sign(x) where z < 0.
fn oct_decode(e: vec2<f32>) -> vec3<f32> {
    var n = vec3<f32>(e, 1.0 - abs(e.x) - abs(e.y));
    let t = max(-n.z, 0.0);
    n.x = n.x + select(t, -t, n.x >= 0.0);
    n.y = n.y + select(t, -t, n.y >= 0.0);
    return normalize(n);
}

// docs/models.md §9 "Graying": y_k(t) = clamp((t − t_k)/GRAY_RAMP_T, 0, 1), smoothstepped
// when `smoothed`; an onset at or past 1 never grays (`agesim_core::layers::hair::gray_fraction`,
// `GRAY_RAMP_T`).
const GRAY_RAMP_T: f32 = 0.08;
fn gray_fraction(t: f32, onset: f32, smoothed: bool) -> f32 {
    if onset >= 1.0 {
        return 0.0;
    }
    let y = clamp((t - onset) / GRAY_RAMP_T, 0.0, 1.0);
    if smoothed {
        return y * y * (3.0 - 2.0 * y);
    }
    return y;
}

// docs/models.md §9 "Miniaturisation": how whole a hair of disappearance age a_k is at age
// t, 0–1: 1 until MINIATURE_T before a_k, falling to 0 at a_k as a smoothstep; a hair that
// never goes (a_k ≥ 1) stays whole (`agesim_core::layers::hair::hair_whole`,
// `MINIATURE_T`).
const MINIATURE_T: f32 = 0.08;
fn hair_whole(disappear_age: f32, t: f32) -> f32 {
    if disappear_age >= 1.0 {
        return 1.0;
    }
    return smoothstep(0.0, MINIATURE_T, disappear_age - t);
}

// Cavity occlusion (docs/models.md §10): `agesim_core::output::compose::{CAVITY,
// CAVITY_MAX, CAVITY_REFERENCE_DISP, CAVITY_RING}`, which the exported GLB's occlusion
// texture uses.
const CAVITY: f32 = 2.0;
const CAVITY_MAX: f32 = 0.7;
const CAVITY_REFERENCE_DISP: f32 = 0.005;
const CAVITY_RING: f32 = 0.5;

// How much a point `local` deeper than the ring of skin around it (normalised depths),
// drawn `disp` deep, is darkened: `1 − agesim_core::output::compose::cavity`.
fn cavity_loss(local: f32, disp: f32) -> f32 {
    return clamp(CAVITY * max(local, 0.0) * max(disp, 0.0) / CAVITY_REFERENCE_DISP, 0.0, CAVITY_MAX);
}

// Crease roughness (docs/models.md §10): `agesim_core::output::compose::{CREASE_ROUGHNESS,
// crease_roughness}`, the exported GLB's metallicRoughnessTexture. The skin's roughness
// where a cavity takes `loss` of the light: up to CREASE_ROUGHNESS rougher at the bottom of
// the deepest crease.
const CREASE_ROUGHNESS: f32 = 0.2;
fn crease_roughness(roughness: f32, loss: f32) -> f32 {
    return clamp(roughness + CREASE_ROUGHNESS * clamp(loss, 0.0, CAVITY_MAX) / CAVITY_MAX, 0.0, 1.0);
}
