//! Eyebrow hairs (docs/models.md §9 "Eyebrows"): short strands grown over each brow of the
//! template (the brow region of [`Regions`]), reaching any head through its fit, drawn by
//! the renderer as blended ribbons like the scalp's hair.
//!
//! A brow is hair, not paint: drawn only in the colour map, the old brow read, blind, as
//! "gray putty ribbons with no individual hairs". Each hair is rooted on a triangle of the
//! head (barycentric coordinates, so it moves with the head's aged shape) and grows in the
//! brow's pattern: upright at the brow's head, toward the temple along its body (the hairs
//! below the arch's middle line slanting up, those above it down, so they meet along it),
//! down at the tail, lying close to the skin. With age a share of them grow long and unruly
//! (the old man's bushy brow) and they gray, hair by hair, with the brows' gray fraction
//! of the aged colour ([`ColourFactors::brow_gray_fraction`]).
//!
//! [`BrowHairs::generate`] places the hairs once per head; [`BrowHairs::strands`] gives
//! each one's curve and colour at an age, for the renderer.

use glam::Vec3;

use crate::age::ColourFactors;
use crate::base::math::smooth01;
use crate::base::rng::Rng;
use crate::head::frame::{BrowPlace, Regions};
use crate::head::mesh::Mesh;

/// Brow hairs per cm² of the brow at its densest, seen from the front (a brow holds about
/// 250–300 hairs in about 2.5 cm²).
pub const DENSITY_PER_CM2: f32 = 130.0;

/// Half the brow's height at its head and at its tail, mm (about 9 mm tall at the head
/// over the eye's inner corner, tapering to 3.6 mm).
const HALF_HEIGHT_MM: (f32, f32) = (4.5, 1.8);

/// How far below the brow's arched middle line (of the colour's regions) its roots are
/// centred, mm: the hairs slant up and lie over it.
const ROOTS_BELOW_MM: f32 = 1.0;

/// Where the brow begins and ends along its eye (0 at the inner corner, 1 at the outer).
const SPAN: (f32, f32) = (-0.22, 1.05);

/// A young hair's length at the brow's head, body and tail, mm.
const LENGTH_MM: [f32; 3] = [5.0, 9.0, 7.0];

/// The share of brow hairs that grow long with age, and how much longer they get at
/// full age (the bushy brow of old men).
const BUSHY_SHARE: f32 = 0.3;
const BUSHY_LENGTHENING: f32 = 0.5;

/// How far a hair rises off the skin at its root, degrees (a young brow lies flat; the
/// grown hairs stand out).
const ELEVATION_DEG: f32 = 5.0;
const BUSHY_ELEVATION_DEG: f32 = 6.0;

/// How far below the root's tangent plane a hair's tip lies, a fraction of its length:
/// where a convex brow has curved away (the skin hides what dips into it on a flat one).
const TIP_DROP: f32 = 0.08;

/// One brow hair at an age, as the renderer draws it (48 bytes): a quadratic Bézier from
/// the root through `middle` to the tip, mesh units, with its gray fraction and shade.
#[repr(C)]
#[derive(Clone, Copy, Debug, PartialEq, bytemuck::Pod, bytemuck::Zeroable)]
pub struct BrowStrand {
    pub root: [f32; 3],
    /// 0 (the hair's colour) to 1 (gray).
    pub gray: f32,
    pub middle: [f32; 3],
    /// A brightness factor around 1 per hair.
    pub shade: f32,
    pub tip: [f32; 3],
    /// How much of a strand's width it covers (finer when gray).
    pub coverage: f32,
}

/// One hair's root and its draws.
#[derive(Clone, Debug, PartialEq)]
struct Root {
    vertices: [u32; 3],
    bary: [f32; 3],
    /// Unit directions in the triangle's plane: along the brow toward the temple, and up
    /// across it.
    lateral: Vec3,
    up: Vec3,
    /// The growth direction's angle from `lateral` toward `up`, radians (young).
    angle: f32,
    /// How far a hair that grows with age turns from `angle` at full growth, radians.
    unruly: f32,
    /// How far the hair curls in the skin's plane by its tip, radians.
    curl: f32,
    /// Young length, mm.
    length_mm: f32,
    elevation: f32,
    /// Whether it grows long with age, and its share of that growth (a man's brow).
    bushy: Option<f32>,
    /// Where along the brow it grows (0 over the eye's inner corner, 1 over the outer),
    /// and its draw against a woman's brow's thinning ([`female_loss`]).
    s: f32,
    loss_draw: f32,
    gray_draw: f32,
    shade: f32,
}

/// The brow hairs of one head.
#[derive(Clone, Debug, PartialEq)]
pub struct BrowHairs {
    roots: Vec<Root>,
    /// Mesh units per mm.
    units_per_mm: f32,
}

impl BrowHairs {
    /// Places the brow hairs on `mesh` (its skin triangles): `template_point` gives each
    /// vertex's template point (metres; `None`: not fitted), `regions` the template's brow
    /// regions, `metres_per_unit` the mesh's units. Per triangle, [`DENSITY_PER_CM2`] ×
    /// (its area on the template's brow seen from the front) hairs are drawn at uniform
    /// barycentric coordinates and kept with the brow's density profile there (full along
    /// its middle, fading to nothing at its top and bottom edges and past its ends).
    /// Deterministic in `seed`.
    pub fn generate(
        mesh: &Mesh,
        template_point: &dyn Fn(usize) -> Option<Vec3>,
        regions: &Regions,
        metres_per_unit: f32,
        seed: u64,
    ) -> Self {
        let positions = mesh.positions();
        let skin = mesh.skin_indices();
        let mm_per_unit = metres_per_unit * 1e3;
        let mut roots = Vec::new();
        for (t, tri) in skin.chunks_exact(3).enumerate() {
            let v = [tri[0], tri[1], tri[2]];
            let places = v.map(|i| template_point(i as usize).and_then(|p| regions.brow_place(p)));
            let [Some(a), Some(b), Some(c)] = places else {
                continue;
            };
            let places = [a, b, c];
            // The two brows' hair meet nowhere: a triangle across the midline has none; nor
            // has one wholly beyond one edge of a brow (above, below, inside or past it).
            let across = places.map(|q| q.across_mm);
            let beyond = |f: &dyn Fn(&BrowPlace) -> bool| places.iter().all(f);
            if places.iter().any(|q| q.side != places[0].side)
                || beyond(&|q| q.across_mm + ROOTS_BELOW_MM > half_height(q.s))
                || beyond(&|q| q.across_mm + ROOTS_BELOW_MM < -half_height(q.s))
                || beyond(&|q| q.s < SPAN.0)
                || beyond(&|q| q.s > SPAN.1)
            {
                continue;
            }
            let p = v.map(|i| positions[i as usize]);
            // The triangle's area on the template's brow seen from the front (out × up,
            // template mm): the same hairs on any head, whatever its triangles' slant or
            // size.
            let d = |k: usize| {
                glam::Vec2::new(
                    places[k].out_mm - places[0].out_mm,
                    places[k].across_mm - places[0].across_mm,
                )
            };
            let area_cm2 = 0.5 * d(1).perp_dot(d(2)).abs() / 100.0;
            if !area_cm2.is_finite() || area_cm2 <= 0.0 {
                continue;
            }
            let Some((lateral, up)) = tangent_frame(p, places.map(|q| q.s), across) else {
                continue;
            };
            let expected = area_cm2 * DENSITY_PER_CM2;
            for (bary, draws) in candidates::<9>(seed ^ 0xb40f_5eed, t as u64, expected) {
                let at = |f: fn(&BrowPlace) -> f32| {
                    bary[0] * f(&places[0]) + bary[1] * f(&places[1]) + bary[2] * f(&places[2])
                };
                let place = BrowPlace {
                    s: at(|q| q.s),
                    out_mm: at(|q| q.out_mm),
                    across_mm: at(|q| q.across_mm),
                    side: places[0].side,
                };
                if draws[0] >= density(&place) {
                    continue;
                }
                roots.push(root(v, bary, lateral, up, &place, &draws));
            }
        }
        Self {
            roots,
            units_per_mm: 1.0 / mm_per_unit,
        }
    }

    pub fn len(&self) -> usize {
        self.roots.len()
    }

    pub fn is_empty(&self) -> bool {
        self.roots.is_empty()
    }

    /// Every hair at an age: `factors` the aged colour's (the brows' gray fraction, and
    /// `contrast`, the old brow's growth), `shape` the head's displacement and displaced
    /// normals at that age (mesh units, per vertex; `None`: the mesh as it is), `female`
    /// whether the brows age as a woman's: they thin, most at the tail, and none grows
    /// long (the bushy old brow is a man's; grown on the panel's women, their white brows
    /// read, blind, as "white bristle brows").
    pub fn strands(
        &self,
        mesh: &Mesh,
        factors: &ColourFactors,
        shape: Option<(&[Vec3], &[Vec3])>,
        female: bool,
    ) -> Vec<BrowStrand> {
        let (positions, normals) = (mesh.positions(), mesh.normals());
        let gray_fraction = factors.brow_gray_fraction();
        let growth = factors.contrast.clamp(0.0, 1.0);
        self.roots
            .iter()
            .filter(|r| !female || r.loss_draw >= growth * female_loss(r.s))
            .map(|r| {
                let (root, normal) = rooted(positions, normals, shape, r.vertices, r.bary);
                let grown = if female {
                    0.0
                } else {
                    r.bushy.map_or(0.0, |g| g * growth)
                };
                let length = r.length_mm * (1.0 + BUSHY_LENGTHENING * grown) * self.units_per_mm;
                let elevation = r.elevation + BUSHY_ELEVATION_DEG.to_radians() * grown;
                // Along the skin in the growth direction (kept in the aged tangent plane).
                let angle = r.angle + r.unruly * grown;
                let along = r.lateral * angle.cos() + r.up * angle.sin();
                let along = (along - normal * along.dot(normal)).normalize_or_zero();
                let out = along * elevation.cos() + normal * elevation.sin();
                // Out of the skin along `out`, then curving back down onto it and to one
                // side: the tip [`TIP_DROP`] below the root's tangent plane, where a convex
                // brow (radius ≈ 3 cm) has curved away from it (a tip above the plane stood
                // off the far brow's outline, read blind as "a flat fan of bristles").
                let side = normal.cross(along);
                let tip_along = along * r.curl.cos() + side * r.curl.sin();
                let middle = root + out * (0.55 * length);
                let tip = root + tip_along * (0.95 * length) - normal * (TIP_DROP * length);
                let gray = smooth01((gray_fraction - r.gray_draw) / 0.08);
                BrowStrand {
                    root: root.to_array(),
                    gray,
                    middle: middle.to_array(),
                    shade: r.shade,
                    tip: tip.to_array(),
                    // Gray brow hair is finer: at a quarter less cover the white
                    // brows read, blind, as "white paint" on dark skin.
                    coverage: 1.0 - 0.45 * gray,
                }
            })
            .collect()
    }
}

/// The candidate roots of one triangle expected to hold `expected` of them (its whole part,
/// and one more with the chance of its fraction): per candidate its uniform barycentric
/// coordinates and `N` draws in [0, 1), the same whether it is kept or not. Seeded by
/// `seed` and the triangle's `stream`.
pub(crate) fn candidates<const N: usize>(
    seed: u64,
    stream: u64,
    expected: f32,
) -> Vec<([f32; 3], [f32; N])> {
    let mut rng = Rng::for_stream(seed, stream);
    let whole = expected.floor();
    let count = whole as u32 + u32::from(rng.next_f32() < expected - whole);
    (0..count)
        .map(|_| {
            let (mut r1, mut r2) = (rng.next_f32(), rng.next_f32());
            if r1 + r2 > 1.0 {
                (r1, r2) = (1.0 - r1, 1.0 - r2);
            }
            let draws = [(); N].map(|_| rng.next_f32());
            ([1.0 - r1 - r2, r1, r2], draws)
        })
        .collect()
}

/// Unit directions in the plane of the triangle `p` along which the coordinates `along`
/// and `across` (one per corner) grow, `across` made square to `along`; `None` on a
/// degenerate triangle or where either does not change over it.
pub(crate) fn tangent_frame(
    p: [Vec3; 3],
    along: [f32; 3],
    across: [f32; 3],
) -> Option<(Vec3, Vec3)> {
    let (e1, e2) = (p[1] - p[0], p[2] - p[0]);
    let n = e1.cross(e2);
    if n == Vec3::ZERO {
        return None;
    }
    let grad = |f: [f32; 3]| {
        ((f[1] - f[0]) * e2.cross(n) + (f[2] - f[0]) * n.cross(e1)) / n.length_squared()
    };
    let lateral = grad(along).normalize_or_zero();
    let across = grad(across);
    let up = (across - lateral * across.dot(lateral)).normalize_or_zero();
    (lateral != Vec3::ZERO && up != Vec3::ZERO).then_some((lateral, up))
}

/// A root's point and unit normal on the triangle `vertices` at `bary`: on the mesh as it
/// is, or displaced by `shape` (per vertex: the displacement and the displaced normal,
/// zero where it has none).
pub(crate) fn rooted(
    positions: &[Vec3],
    normals: &[Vec3],
    shape: Option<(&[Vec3], &[Vec3])>,
    vertices: [u32; 3],
    bary: [f32; 3],
) -> (Vec3, Vec3) {
    let vertex = |k: usize| {
        let i = vertices[k] as usize;
        match shape {
            Some((delta, shaped)) if i < delta.len() && i < shaped.len() => {
                let n = if shaped[i] == Vec3::ZERO {
                    normals[i]
                } else {
                    shaped[i]
                };
                (positions[i] + delta[i], n)
            }
            _ => (positions[i], normals[i]),
        }
    };
    let (mut root, mut normal) = (Vec3::ZERO, Vec3::ZERO);
    for (k, &b) in bary.iter().enumerate() {
        let (p, n) = vertex(k);
        root += p * b;
        normal += n * b;
    }
    (root, normal.normalize_or_zero())
}

/// A hair rooted at `bary` on the triangle `vertices`, grown by the brow's pattern at
/// `place` and its draws (uniform in [0, 1)).
fn root(
    vertices: [u32; 3],
    bary: [f32; 3],
    lateral: Vec3,
    up: Vec3,
    place: &BrowPlace,
    draws: &[f32; 9],
) -> Root {
    let s = place.s;
    let y = (place.across_mm + ROOTS_BELOW_MM) / half_height(s);
    // The pattern, degrees from the temple-ward direction toward up: upright at the head,
    // along the body (slanting up below the middle line and down above it, meeting
    // along it), down at the tail.
    let body = 15.0 + (-10.0 - 15.0) * smooth01(0.5 + y);
    let mut angle = 60.0 + (body - 60.0) * smooth01((s - 0.05) / 0.25);
    angle += (-20.0 - angle) * smooth01((s - 0.75) / 0.35);
    angle += (draws[1] - 0.5) * 16.0;
    let head_body_tail = if s < 0.35 {
        LENGTH_MM[0] + (LENGTH_MM[1] - LENGTH_MM[0]) * smooth01(s / 0.35)
    } else {
        LENGTH_MM[1] + (LENGTH_MM[2] - LENGTH_MM[1]) * smooth01((s - 0.7) / 0.4)
    };
    let bushy = (draws[3] < BUSHY_SHARE).then(|| 0.5 + draws[4]);
    // The grown hairs are unruly: up to ±12° more at full growth.
    let unruly = if bushy.is_some() {
        (draws[7] - 0.5) * 24.0
    } else {
        0.0
    };
    Root {
        vertices,
        bary,
        lateral,
        up,
        angle: angle.to_radians(),
        unruly: unruly.to_radians(),
        // ±12° (from the angle's draw's other digits): straight hairs read, blind, as
        // "stiff spiky needles".
        curl: ((draws[1] * 7.0).fract() - 0.5) * 24f32.to_radians(),
        length_mm: head_body_tail * (0.8 + 0.4 * draws[2]),
        elevation: (ELEVATION_DEG + (draws[5] - 0.5) * 8.0).to_radians(),
        bushy,
        s,
        loss_draw: draws[3],
        // The grown, wiry hairs gray as the others do: graying first, they stood out
        // long and white over the dark ones, read blind on dark skin as "white brow
        // tufts" (rounds 53–54).
        gray_draw: draws[6],
        shade: 0.8 + 0.4 * draws[8],
    }
}

/// The share of a woman's brow hairs lost at full age at `s` along the brow: a third over
/// its head and body, two thirds at its tail (the lateral brow thins first and most with
/// age in women; docs/models.md §9 "Eyebrows").
pub fn female_loss(s: f32) -> f32 {
    FEMALE_LOSS.0 + (FEMALE_LOSS.1 - FEMALE_LOSS.0) * smooth01((s - 0.45) / 0.55)
}

/// See [`female_loss`]: (head and body, tail).
const FEMALE_LOSS: (f32, f32) = (0.3, 0.65);

/// The brow's half height at `s` along it, mm.
fn half_height(s: f32) -> f32 {
    let (head, tail) = HALF_HEIGHT_MM;
    head + (tail - head) * smooth01((s - 0.1) / 1.0)
}

/// The brow's hair density at a place, 0–1 of [`DENSITY_PER_CM2`]: full near its middle
/// line, fading over the outer third of its height and past its ends.
fn density(p: &BrowPlace) -> f32 {
    let h = half_height(p.s);
    let across = 1.0 - smooth01(((p.across_mm + ROOTS_BELOW_MM).abs() - 0.6 * h) / (0.4 * h));
    let along = smooth01((p.s - SPAN.0) / 0.15) * (1.0 - smooth01((p.s - (SPAN.1 - 0.2)) / 0.2));
    across * along
}

#[cfg(test)]
mod tests;
