//! A scalp hair's strand at an age, on the CPU: the curve, the coil and the colour the hair
//! pass draws (`shaders/common.wgsl`: `hair_curve`, `coiled`, `strand_length`; hair.wgsl's
//! colour), so that the hair leaving agesim in a GLB is the hair the view shows
//! (docs/models.md §9 "The hair in the GLB"). A GPU test (`crates/render/tests/twins.rs`)
//! runs the shader's functions and compares them with these.

use glam::Vec3;

use super::{GrayingRamp, HairInstance, gray_fraction, hair_whole};

/// How the hair is styled, the same for every hair (the view's hair shading).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct StrandStyle {
    /// The hair's length, mesh units (each hair ±15 % by its random number).
    pub length: f32,
    /// How far the hair bends from its growth direction down along the scalp, 0–1.
    pub droop: f32,
    /// How curled, 0 straight – 1 coiled.
    pub curl: f32,
}

/// Turns of a coiled hair's helix (`COIL_TURNS`).
pub const COIL_TURNS: f32 = 1.6;
/// The helix's radius over the hair's length at full curl (`COIL_RADIUS`).
pub const COIL_RADIUS: f32 = 0.14;

/// A strand's quadratic Bézier: root, middle control point, tip.
pub type Curve = [Vec3; 3];

/// The hair as a quadratic Bézier (common.wgsl `hair_curve`): out of the scalp along `dir`,
/// then combed back and down along the scalp as far as `droop` says, its comb turned by a
/// smooth field of the root's position in hair lengths (`unit`) and by the hair's own
/// `random` number, a coiled hair leaning every way.
pub fn hair_curve(
    root: Vec3,
    dir: Vec3,
    len: f32,
    random: f32,
    curl: f32,
    droop: f32,
    unit: f32,
) -> Curve {
    let droop = droop.clamp(0.0, 1.0) * (1.0 - 0.65 * curl);
    let g = Vec3::new(0.0, -0.5, -1.0).normalize();
    let along = g - dir * g.dot(dir);
    let mut comb = if along.length() > 1e-3 {
        along.normalize()
    } else {
        dir
    };
    let q = root / unit.max(1e-9);
    let flow = 0.22 * (q.dot(Vec3::new(0.61, 0.37, -0.52)) + 1.7).sin()
        + 0.13 * (q.dot(Vec3::new(-0.29, 0.83, 0.47)) * 1.9 + 0.4).sin();
    let turn =
        flow + (fract(random * 13.0) - 0.5) * 0.25 + (fract(random * 41.0) - 0.5) * 2.8 * curl;
    comb = comb * turn.cos() + dir.cross(comb) * turn.sin();
    let r = fract(random * 29.0);
    let r3 = r * r * r;
    let stand = mix(0.05, 0.18, r3 * r3);
    let p1 = root + dir * (len * mix(0.5, stand, droop));
    let p2 = p1 + dir.lerp(comb, droop).normalize() * (len * mix(0.5, 0.92, droop))
        - dir * (len * 0.12 * droop);
    [root, p1, p2]
}

/// The curve's point at `s` ∈ [0, 1].
pub fn curve_point(c: &Curve, s: f32) -> Vec3 {
    let r = 1.0 - s;
    c[0] * (r * r) + c[1] * (2.0 * r * s) + c[2] * (s * s)
}

/// The curve's unit tangent at `s`.
pub fn curve_tangent(c: &Curve, s: f32) -> Vec3 {
    ((c[1] - c[0]) * (1.0 - s) + (c[2] - c[1]) * s).normalize()
}

/// A coiled hair's point and tangent (common.wgsl `coiled`): the curve's point `p`
/// (tangent `tangent`, `s` along it) wound round the curve in a helix of [`COIL_TURNS`]
/// turns, its radius growing from the root to [`COIL_RADIUS`] of the length times `curl`.
pub fn coiled(p: Vec3, tangent: Vec3, len: f32, s: f32, random: f32, curl: f32) -> (Vec3, Vec3) {
    let a = if tangent.x.abs() > 0.9 {
        Vec3::Y
    } else {
        Vec3::X
    };
    let b1 = tangent.cross(a).normalize();
    let b2 = tangent.cross(b1);
    let phase = std::f32::consts::TAU * (COIL_TURNS * s + fract(random * 17.0));
    let r = curl * COIL_RADIUS * len * smoothstep(0.0, 0.3, s);
    let round = b1 * phase.cos() + b2 * phase.sin();
    let along = -b1 * phase.sin() + b2 * phase.cos();
    let t = (tangent * len + along * (r * std::f32::consts::TAU * COIL_TURNS)).normalize();
    (p + round * r, t)
}

/// A hair's length at age `t` (common.wgsl `strand_length`): the style's, times the hair's
/// taper and its ±15 %, a coiled hair seen whole a little over half as long, and a hair
/// about to go shortened to a vellus hair (docs/models.md §9 "Miniaturisation").
pub fn strand_length(length: f32, length_factor: f32, random: f32, curl: f32, whole: f32) -> f32 {
    length * length_factor * (0.85 + 0.3 * random) * (1.0 - 0.45 * curl) * mix(0.35, 1.0, whole)
}

/// One hair at age `t`: `segments + 1` points from root to tip with their tangents, as the
/// hair pass places its ribbon's spine; empty when the hair is gone.
pub fn strand(h: &HairInstance, style: &StrandStyle, t: f32, segments: u32) -> Vec<(Vec3, Vec3)> {
    if !super::transition::hair_present(h.disappear_age(), t) {
        return Vec::new();
    }
    let random = h.random_as_drawn();
    let curl = style.curl.clamp(0.0, 1.0);
    let whole = hair_whole(h.disappear_age(), t);
    let len = strand_length(style.length, h.length_factor(), random, curl, whole);
    if !(len > 0.0 && len.is_finite()) {
        return Vec::new();
    }
    let curve = hair_curve(
        h.position(),
        h.direction(),
        len,
        random,
        curl,
        style.droop,
        style.length,
    );
    (0..=segments.max(1))
        .map(|k| {
            let s = k as f32 / segments.max(1) as f32;
            let (p, tangent) = (curve_point(&curve, s), curve_tangent(&curve, s));
            if curl > 0.0 {
                coiled(p, tangent, len, s, random, curl)
            } else {
                (p, tangent)
            }
        })
        .collect()
}

/// A hair's colour at age `t` (hair.wgsl): its pigmented shade (0.8–1.2 of `base`) or, as
/// it grays (its own onset: [`gray_fraction`]), its own shade of gray (0.45–1.10 of
/// `gray`), linear RGB; and the gray fraction.
pub fn strand_colour(
    h: &HairInstance,
    base: Vec3,
    gray: Vec3,
    t: f32,
    ramp: GrayingRamp,
) -> (Vec3, f32) {
    let random = h.random_as_drawn();
    let y = gray_fraction(t, h.graying_onset(), ramp);
    let pigmented = base * (0.8 + 0.4 * random);
    let white = gray * (0.45 + 0.65 * fract(random * 7.0));
    (pigmented.lerp(white, y), y)
}

/// A strand to lay as a ribbon: its points with their tangents from root to tip, the
/// direction the ribbon lies across (its growth direction), its colour and root width.
type Ribbon = (Vec<(Vec3, Vec3)>, Vec3, Vec3, f32);

/// How the exported hair looks: the view's style and colours at the age, and its ribbons'
/// width.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct HairLook {
    pub style: StrandStyle,
    /// The hair's pigmented and gray colours and the brows', linear RGB.
    pub base: Vec3,
    pub gray: Vec3,
    pub brow: Vec3,
    pub ramp: GrayingRamp,
    /// A ribbon's width at the root, mesh units (a third of it at the tip).
    pub width: f32,
}

/// The hair of an age as one triangle mesh (the GLB's `hair`): each strand a ribbon of
/// `segments` quads along the curve the view draws, lying across its growth direction,
/// tapering to a third at the tip, coloured as the view colours it (each hair pigmented
/// or gray); one scalp hair in `stride` (its ribbon `stride` times as wide, so the hair
/// covers the scalp as densely), then the brows and the lashes.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct HairMesh {
    pub positions: Vec<Vec3>,
    pub normals: Vec<Vec3>,
    /// Linear RGBA, 16-bit.
    pub colours: Vec<[u16; 4]>,
    pub indices: Vec<u32>,
}

impl HairMesh {
    /// The scalp hair present at `t` (one in `stride`) and the `brows` (brow hairs and
    /// lashes at that age).
    pub fn new(
        hairs: &super::HairInstances,
        brows: &[super::brows::BrowStrand],
        look: &HairLook,
        t: f32,
        stride: usize,
        segments: u32,
    ) -> Self {
        use rayon::prelude::*;
        let stride = stride.max(1);
        let present = &hairs.instances()[..hairs.count(t).min(hairs.len())];
        let width = look.width * stride as f32;
        let scalp: Vec<Ribbon> = present
            .par_iter()
            .step_by(stride)
            .map(|h| {
                let (colour, _) = strand_colour(h, look.base, look.gray, t, look.ramp);
                (
                    strand(h, &look.style, t, segments),
                    h.direction(),
                    colour,
                    width,
                )
            })
            .collect();
        let brow_strands = brows.iter().map(|b| {
            let curve = [b.root, b.middle, b.tip].map(Vec3::from);
            let points = (0..=segments.max(1))
                .map(|k| {
                    let s = k as f32 / segments.max(1) as f32;
                    (curve_point(&curve, s), curve_tangent(&curve, s))
                })
                .collect();
            let base = look.brow * b.shade;
            let gray = look.gray * Vec3::new(1.0, 0.97, 0.92) * (0.5 + 0.4 * b.shade);
            (
                points,
                Vec3::Z,
                base.lerp(gray, b.gray),
                look.width * b.coverage.clamp(0.2, 1.0),
            )
        });
        let mut mesh = Self::default();
        for (points, up, colour, width) in scalp.into_iter().chain(brow_strands) {
            mesh.ribbon(&points, up, colour, width);
        }
        mesh
    }

    /// One strand's ribbon: `points` (with tangents) from root to tip, across `up`.
    fn ribbon(&mut self, points: &[(Vec3, Vec3)], up: Vec3, colour: Vec3, width: f32) {
        let finite = points.iter().all(|(p, t)| p.is_finite() && t.is_finite());
        if points.len() < 2 || !finite || !width.is_finite() || width <= 0.0 {
            return;
        }
        let rgba = {
            let c = colour.clamp(Vec3::ZERO, Vec3::ONE).to_array();
            let q = |x: f32| (x * 65535.0).round() as u16;
            [q(c[0]), q(c[1]), q(c[2]), u16::MAX]
        };
        // One side for the whole strand, so the ribbon does not twist: across the strand
        // from its root to its tip and `up` (at the root the hair leaves along `up` and the
        // two are parallel), else any direction across `up`; at each point made square to
        // the strand there.
        let (root, tip) = (points[0].0, points[points.len() - 1].0);
        let side = (tip - root)
            .cross(up)
            .try_normalize()
            .unwrap_or_else(|| up.normalize_or(Vec3::Y).any_orthonormal_vector());
        let first = self.positions.len() as u32;
        let last = (points.len() - 1) as f32;
        for (k, &(p, t)) in points.iter().enumerate() {
            let across = (side - t * t.dot(side)).try_normalize().unwrap_or(side);
            let mut n = across.cross(t).normalize_or(up);
            if n.dot(up) < 0.0 {
                n = -n;
            }
            let half = 0.5 * width * (1.0 - 0.65 * k as f32 / last);
            for side in [-1.0, 1.0] {
                self.positions.push(p + across * (half * side));
                self.normals.push(n);
                self.colours.push(rgba);
            }
        }
        for k in 0..points.len() as u32 - 1 {
            let (a, b) = (first + 2 * k, first + 2 * k + 2);
            self.indices
                .extend_from_slice(&[a, a + 1, b + 1, a, b + 1, b]);
        }
    }

    /// Strands in the mesh.
    pub fn triangle_count(&self) -> usize {
        self.indices.len() / 3
    }

    /// The bytes the mesh takes in a GLB (positions, normals, 16-bit colours, indices).
    pub fn glb_bytes(&self) -> usize {
        self.positions.len() * (12 + 12 + 8) + self.indices.len() * 4
    }
}

fn fract(x: f32) -> f32 {
    x - x.floor()
}

fn mix(a: f32, b: f32, t: f32) -> f32 {
    a + (b - a) * t
}

fn smoothstep(e0: f32, e1: f32, x: f32) -> f32 {
    let t = ((x - e0) / (e1 - e0)).clamp(0.0, 1.0);
    t * t * (3.0 - 2.0 * t)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_straight_hair_leaves_the_scalp_and_lies_back_along_it() {
        let root = Vec3::new(0.0, 0.1, 0.05);
        let dir = Vec3::new(0.0, 1.0, 0.3).normalize();
        let c = hair_curve(root, dir, 0.05, 0.3, 0.0, 0.8, 0.05);
        assert_eq!(c[0], root);
        // Out along its direction first, then back (−z) and not far above the root.
        assert!((c[1] - root).dot(dir) > 0.0);
        assert!(c[2].z < c[1].z, "{c:?}");
        // Its length along the curve is about the hair's.
        let len: f32 = (0..16)
            .map(|k| {
                curve_point(&c, (k + 1) as f32 / 16.0).distance(curve_point(&c, k as f32 / 16.0))
            })
            .sum();
        assert!((0.035..0.06).contains(&len), "{len}");
        // Straight: no coil.
        let t = curve_tangent(&c, 0.5);
        assert!((t.length() - 1.0).abs() < 1e-5);
    }

    #[test]
    fn a_coiled_hair_winds_round_its_curve() {
        let (p, t) = (Vec3::ZERO, Vec3::Y);
        let (at_root, _) = coiled(p, t, 0.04, 0.0, 0.2, 1.0);
        assert!(at_root.length() < 1e-7, "starts at the root");
        let radii: Vec<f32> = (4..=10)
            .map(|k| coiled(p, t, 0.04, k as f32 / 10.0, 0.2, 1.0).0.length())
            .collect();
        for r in radii {
            assert!((r - COIL_RADIUS * 0.04).abs() < 1e-6, "{r}");
        }
    }

    #[test]
    fn the_hair_mesh_is_a_ribbon_per_strand_coloured_by_its_graying() {
        use crate::layers::hair::brows::BrowStrand;
        let hairs = crate::layers::hair::tests::some_hairs();
        let look = HairLook {
            style: StrandStyle {
                length: 0.05,
                droop: 0.8,
                curl: 0.0,
            },
            base: Vec3::new(0.05, 0.03, 0.02),
            gray: Vec3::new(0.6, 0.58, 0.55),
            brow: Vec3::new(0.03, 0.02, 0.01),
            ramp: GrayingRamp::Linear,
            width: 1e-4,
        };
        let brow = BrowStrand {
            root: [0.0, 0.1, 0.1],
            gray: 1.0,
            middle: [0.003, 0.101, 0.1],
            shade: 1.0,
            tip: [0.006, 0.101, 0.1],
            coverage: 1.0,
        };
        let (t, segments) = (0.6, 3);
        let mesh = HairMesh::new(&hairs, &[brow], &look, t, 1, segments);
        let present = hairs.count(t);
        assert!(present > 0 && present < hairs.len());
        // 2 vertices a point, 2 triangles a segment, for every hair present and the brow.
        let strands = present + 1;
        assert_eq!(mesh.positions.len(), strands * 2 * (segments as usize + 1));
        assert_eq!(mesh.triangle_count(), strands * 2 * segments as usize);
        assert!(
            mesh.indices
                .iter()
                .all(|&i| (i as usize) < mesh.positions.len())
        );
        // Each hair's colour is its own: pigmented ones dark, gray ones light.
        let (dark, light) = mesh.colours.iter().fold((0, 0), |(d, l), c| {
            (
                d + usize::from(c[0] < 10_000),
                l + usize::from(c[0] > 20_000),
            )
        });
        assert!(dark > 0 && light > 0, "{dark} dark, {light} light");
        // The ribbon at the root is the width asked for, a third of it at the tip.
        let root = mesh.positions[0].distance(mesh.positions[1]);
        let tip = mesh.positions[2 * segments as usize]
            .distance(mesh.positions[2 * segments as usize + 1]);
        assert!(
            (root - 1e-4).abs() < 1e-7 && (tip - 0.35e-4).abs() < 1e-7,
            "{root} {tip}"
        );
        // The ribbons do not twist: along each strand the vertex pairs' sides agree.
        let per = 2 * (segments as usize + 1);
        for strand in mesh.positions.chunks_exact(per) {
            let sides: Vec<Vec3> = strand
                .chunks_exact(2)
                .map(|p| (p[1] - p[0]).normalize())
                .collect();
            for w in sides.windows(2) {
                assert!(w[0].dot(w[1]) > 0.5, "a twisted ribbon: {w:?}");
            }
        }
        // A hair of no length is no ribbon (no NaN in the mesh).
        let none = HairLook {
            style: StrandStyle {
                length: 0.0,
                ..look.style
            },
            ..look
        };
        let empty = HairMesh::new(&hairs, &[], &none, t, 1, segments);
        assert!(
            empty.positions.is_empty(),
            "{} vertices",
            empty.positions.len()
        );
        // Fewer hairs, wider.
        let light_mesh = HairMesh::new(&hairs, &[], &look, t, 4, segments);
        assert_eq!(
            light_mesh.positions.len(),
            present.div_ceil(4) * 2 * (segments as usize + 1)
        );
        assert!((light_mesh.positions[0].distance(light_mesh.positions[1]) - 4e-4).abs() < 1e-7);
    }

    #[test]
    fn a_hair_about_to_go_is_shorter_and_a_gone_one_is_not_drawn() {
        assert!(
            strand_length(0.05, 1.0, 0.5, 0.0, 0.0) < 0.4 * strand_length(0.05, 1.0, 0.5, 0.0, 1.0)
        );
        assert!(
            strand_length(0.05, 1.0, 0.5, 1.0, 1.0) < 0.6 * strand_length(0.05, 1.0, 0.5, 0.0, 1.0)
        );
    }
}
