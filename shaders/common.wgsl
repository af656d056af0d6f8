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

// docs/models.md §9 "Cover": the share of its cover a white scalp hair keeps, against a
// pigmented one's (`agesim_core::layers::hair::WHITE_SCALP_HAIR_COVER`).
const WHITE_HAIR_COVER: f32 = 0.6;

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

// The hair as a quadratic Bézier: out of the scalp along its direction for up to half of
// its length, then combed along the scalp, back and down (the comb direction projected
// onto the plane across the hair's root direction: swept back from the hairline, down at
// the back, back and down over the ears), so hair lies on the head instead of standing
// like bristles or falling over the brow. The head is in the standard frame (+y up, +z
// forward). `droop_in` ∈ [0, 1] is how far it bends (0: straight along its direction),
// `unit` the hair's length (the comb's field is in hair lengths). The CPU's twin:
// `agesim_core::layers::hair::strand` (the GLB's hair).
struct HairCurve {
    p0: vec3<f32>,
    p1: vec3<f32>,
    p2: vec3<f32>,
}

fn hair_curve(root: vec3<f32>, dir: vec3<f32>, len: f32, random: f32, curl: f32, droop_in: f32, unit: f32) -> HairCurve {
    // Coiled hair is not combed flat: it stands off the scalp (a third of the droop).
    let droop = clamp(droop_in, 0.0, 1.0) * (1.0 - 0.65 * curl);
    let g = normalize(vec3<f32>(0.0, -0.5, -1.0));
    let along = g - dir * dot(g, dir);
    // Where the comb is parallel to the hair there is no combing direction: stay straight.
    var comb = select(dir, normalize(along), length(along) > 1e-3);
    // The comb's way wanders over the scalp, up to ±20° over a few centimetres (a smooth
    // field of the root's position in hair lengths, so the same on any head's units):
    // hair lies in locks that flow (combed all one way, the fringe read, blind, as "a
    // flat, streaky painted band"); and each hair its own way within that, up to ±7°
    // (from its random number's other digits; ±20° each read as static).
    let q = root / max(unit, 1e-9);
    let flow = 0.22 * sin(dot(q, vec3<f32>(0.61, 0.37, -0.52)) + 1.7)
        + 0.13 * sin(dot(q, vec3<f32>(-0.29, 0.83, 0.47)) * 1.9 + 0.4);
    // Coiled hair leans every way (up to ±80° more, from the random number's other digits).
    let turn = flow + (fract(random * 13.0) - 0.5) * 0.25 + (fract(random * 41.0) - 0.5) * 2.8 * curl;
    comb = comb * cos(turn) + cross(dir, comb) * sin(turn);
    // Most hair lies flat (stands 5 % of its length); about one in six stands up to 18 %
    // (flyaways, from the random number's other digits), so the silhouette of the hair
    // is broken into strands instead of a solid band.
    let r = fract(random * 29.0);
    let r3 = r * r * r;
    let stand = mix(0.05, 0.18, r3 * r3);
    let p1 = root + dir * (len * mix(0.5, stand, droop));
    // The tip bends back toward the scalp (as far as a head's curvature takes it from a
    // straight hair), so hair lies on it instead of flaring where the head curves away.
    let p2 = p1 + normalize(mix(dir, comb, droop)) * (len * mix(0.5, 0.92, droop))
        - dir * (len * 0.12 * droop);
    return HairCurve(root, p1, p2);
}

fn curve_point(c: HairCurve, s: f32) -> vec3<f32> {
    let r = 1.0 - s;
    return c.p0 * (r * r) + c.p1 * (2.0 * r * s) + c.p2 * (s * s);
}

fn curve_tangent(c: HairCurve, s: f32) -> vec3<f32> {
    return normalize((c.p1 - c.p0) * (1.0 - s) + (c.p2 - c.p1) * s);
}

struct Coil {
    p: vec3<f32>,
    tangent: vec3<f32>,
}

// A coiled hair (docs/models.md §9 "Curl"): the curve's point `p` (tangent `tangent`, `s`
// along it) wound round the curve in a helix of COIL_TURNS turns, its radius growing from
// the root to COIL_RADIUS of the length times `curl`, each hair at its own phase.
const COIL_TURNS: f32 = 1.6;
const COIL_RADIUS: f32 = 0.14;
fn coiled(p: vec3<f32>, tangent: vec3<f32>, len: f32, s: f32, random: f32, curl: f32) -> Coil {
    let a = select(vec3<f32>(1.0, 0.0, 0.0), vec3<f32>(0.0, 1.0, 0.0), abs(tangent.x) > 0.9);
    let b1 = normalize(cross(tangent, a));
    let b2 = cross(tangent, b1);
    let phase = 6.2831853 * (COIL_TURNS * s + fract(random * 17.0));
    let r = curl * COIL_RADIUS * len * smoothstep(0.0, 0.3, s);
    let round = b1 * cos(phase) + b2 * sin(phase);
    let along = -b1 * sin(phase) + b2 * cos(phase);
    let t = normalize(tangent * len + along * (r * 6.2831853 * COIL_TURNS));
    return Coil(p + round * r, t);
}

// A hair's length at age t (`agesim_core::layers::hair::strand::strand_length`): the
// style's, times its taper and ±15 % by its random number; a coiled hair seen whole spans
// a little over half its length (its coils take the rest); a hair about to go shortened
// (`whole`: `hair_whole`).
fn strand_length(length: f32, length_factor: f32, random: f32, curl: f32, whole: f32) -> f32 {
    return length * length_factor * (0.85 + 0.3 * random) * (1.0 - 0.45 * curl) * mix(0.35, 1.0, whole);
}
