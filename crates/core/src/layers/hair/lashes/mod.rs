//! Eyelashes (docs/models.md §9 "Eyelashes"): a fringe of dark curved hairs along the
//! margin of each upper lid of the template, reaching any head through its fit, drawn by
//! the renderer as the brows' strands are ([`BrowStrand`]).
//!
//! The default head's eyes are closed: without lashes its lids read, blind, as "a death
//! mask". On closed eyes the upper lashes hang down over the slit between the lids and
//! curl out, away from the face; they fan toward the temple at the outer corner and
//! toward the nose at the inner one. With age they thin out, shorten and a few gray (they
//! gray later than the brows).
//!
//! [`Lashes::generate`] places them once per head; [`Lashes::strands`] gives each one's
//! curve and colour at an age.

use glam::Vec3;

use crate::age::ColourFactors;
use crate::base::math::smooth01;
use crate::head::frame::{LidPlace, Regions};
use crate::head::mesh::Mesh;
use crate::layers::hair::brows::{BrowStrand, candidates, rooted, tangent_frame};

/// Lashes per cm² of the root band (an upper lid carries 90–160 lashes in two or three
/// rows along about 3 cm of its margin: about 120 in a 3 cm × 1.2 mm band).
pub const DENSITY_PER_CM2: f32 = 250.0;

/// The band of the upper lid the roots grow from, mm above the slit between the lids.
const BAND_MM: (f32, f32) = (0.2, 1.4);

/// How far a triangle must face forward on the template (its normal's +Z) to carry lashes.
const FACING: f32 = 0.5;

/// Where the lashes begin and end along the eye (0 at its inner corner, 1 at its outer).
const SPAN: (f32, f32) = (0.06, 1.0);

/// A young lash's length at the inner end, the longest (at 0.6 of the way out) and the
/// outer end, mm.
const LENGTH_MM: [f32; 3] = [6.0, 10.0, 7.0];

/// How far a lash leaves the lid at its root, and how much further it has turned away
/// from the face by its tip (the curl), degrees.
const ELEVATION_DEG: f32 = 30.0;
const CURL_DEG: f32 = 45.0;

/// How far the lashes fan out sideways from straight down, degrees per unit of the way
/// along the eye from [`FAN_CENTRE`] (toward the temple outside it, the nose inside).
const FAN_DEG: f32 = 50.0;
const FAN_CENTRE: f32 = 0.45;

/// The share of lashes lost, and how much shorter the rest are, at full age (the
/// lashes thin with age; a third lost and a fifth shorter read, blind, at 80 as "dark,
/// lush, young lashes, like mascara").
const LOSS: f32 = 0.5;
const SHORTENING: f32 = 0.3;

/// How much of their curl the lashes lose at full age: they straighten and droop as the
/// lid hoods (lash ptosis comes with dermatochalasis). Curled as young ones under the
/// lowered, hooding lid of 80, their tips turned up through the fold of skin over them,
/// read blind as "lashes poke up through the drooping upper lids as black ticks" on four
/// heads (round 47).
const UNCURL: f32 = 0.6;

/// The lashes gray this much later than the brows: a lash is gray when its draw is under
/// this × the brows' gray fraction.
const GRAY_LAG: f32 = 0.25;

/// On open eyes (a head with eyeballs), the template's closed lids' slit lies on the
/// head's lower lid margin, and the lashes rooted over it are lower lashes: this share of
/// them, this much of the upper lashes' length (lower lashes are fewer and about half as
/// long: Thibaut et al. 2010). Drawn as the upper ones, long and dense, they hung over the
/// open eyes' lower lids, read blind as "spiky lower lashes", "spidery dark fans under
/// slit eyes" (rounds 12–14).
const LOWER_SHARE: f32 = 0.35;
const LOWER_LENGTH: f32 = 0.5;

/// One lash: where it is rooted and its draws.
#[derive(Clone, Debug, PartialEq)]
struct Lash {
    vertices: [u32; 3],
    bary: [f32; 3],
    /// Unit directions in the triangle's plane: along the eye toward its outer corner, and
    /// up across the lid.
    lateral: Vec3,
    up: Vec3,
    /// The sideways turn from straight down, radians (toward `lateral` when positive).
    fan: f32,
    /// Off the lid at the root, radians.
    elevation: f32,
    /// How much further it turns off the lid by its tip, radians (negative: back toward
    /// the lid's plane, as an open eye's upper lashes curl up).
    curl: f32,
    /// The direction it leaves in instead of the skin's normal at its root (an open eye's
    /// upper lashes: the eyeball's forward there).
    out: Option<Vec3>,
    /// Young length, mm.
    length_mm: f32,
    /// Lost with age once the age's loss passes it.
    loss_draw: f32,
    gray_draw: f32,
    shade: f32,
}

/// The lashes of one head.
#[derive(Clone, Debug, PartialEq)]
pub struct Lashes {
    lashes: Vec<Lash>,
    /// Mesh units per mm.
    units_per_mm: f32,
}

impl Lashes {
    /// Places the lashes on `mesh` (its skin triangles): `template_point` gives each
    /// vertex's template point (metres; `None`: not fitted), `regions` the template's
    /// lids, `metres_per_unit` the mesh's units. Per triangle facing forward (on the
    /// template), on the band
    /// [`BAND_MM`] above the slit, [`DENSITY_PER_CM2`] × (its area across the lid) lashes
    /// at uniform barycentric coordinates, kept with the fringe's density along the eye.
    /// `open`: the head's eyes are open (it has eyeballs), so these are lower lashes.
    /// Deterministic in `seed`.
    pub fn generate(
        mesh: &Mesh,
        template_point: &dyn Fn(usize) -> Option<Vec3>,
        regions: &Regions,
        metres_per_unit: f32,
        seed: u64,
        open: bool,
    ) -> Self {
        let positions = mesh.positions();
        let skin = mesh.skin_indices();
        let mut lashes = Vec::new();
        for (t, tri) in skin.chunks_exact(3).enumerate() {
            let v = [tri[0], tri[1], tri[2]];
            let [Some(ta), Some(tb), Some(tc)] = v.map(|i| template_point(i as usize)) else {
                continue;
            };
            // Only the lid's front: where the closed upper lid overhangs the lower one, the
            // surface folds under itself, and its underside would grow a second fringe
            // pointing up.
            if (tb - ta).cross(tc - ta).normalize_or_zero().z < FACING {
                continue;
            }
            let places = [ta, tb, tc].map(|p| regions.lid_place(p));
            let [Some(a), Some(b), Some(c)] = places else {
                continue;
            };
            let places = [a, b, c];
            let beyond = |f: &dyn Fn(&LidPlace) -> bool| places.iter().all(f);
            if places.iter().any(|q| q.side != places[0].side)
                || beyond(&|q| q.across_mm < BAND_MM.0)
                || beyond(&|q| q.across_mm > BAND_MM.1)
                || beyond(&|q| q.s < SPAN.0)
                || beyond(&|q| q.s > SPAN.1)
            {
                continue;
            }
            // The triangle's area on the lid, along × across (template mm): the same count
            // on any head, whatever its triangles.
            let d = |k: usize| {
                glam::Vec2::new(
                    (places[k].s - places[0].s) * places[0].length_mm,
                    places[k].across_mm - places[0].across_mm,
                )
            };
            let area_cm2 = 0.5 * d(1).perp_dot(d(2)).abs() / 100.0;
            if !area_cm2.is_finite() || area_cm2 <= 0.0 {
                continue;
            }
            let p = v.map(|i| positions[i as usize]);
            let Some((lateral, up)) =
                tangent_frame(p, places.map(|q| q.s), places.map(|q| q.across_mm))
            else {
                continue;
            };
            let expected = area_cm2 * DENSITY_PER_CM2;
            for (bary, draws) in candidates::<7>(seed ^ 0x1a5_4e55, t as u64, expected) {
                let at = |f: fn(&LidPlace) -> f32| {
                    bary[0] * f(&places[0]) + bary[1] * f(&places[1]) + bary[2] * f(&places[2])
                };
                let (s, across) = (at(|q| q.s), at(|q| q.across_mm));
                if !(BAND_MM.0..=BAND_MM.1).contains(&across) || draws[0] >= density(s) {
                    continue;
                }
                let fan = FAN_DEG * (s - FAN_CENTRE) + (draws[1] - 0.5) * 16.0;
                lashes.push(Lash {
                    vertices: v,
                    bary,
                    lateral,
                    up,
                    fan: fan.to_radians(),
                    elevation: (ELEVATION_DEG + (draws[2] - 0.5) * 16.0).to_radians(),
                    curl: CURL_DEG.to_radians(),
                    out: None,
                    length_mm: length_mm(s) * (0.8 + 0.4 * draws[3]),
                    loss_draw: draws[4],
                    gray_draw: draws[5],
                    shade: 0.7 + 0.3 * draws[6],
                });
            }
        }
        if open {
            // Both lids' lashes on the head's own margins ([`open`]); where no lower
            // margin is found, the template's lashes are the lower ones.
            let balls = open::eyeballs(mesh);
            let mm = 1e-3 / metres_per_unit;
            let lower = open::margin_lashes(mesh, &balls, mm, seed, open::Lid::Lower);
            if lower.is_empty() {
                // Which stay: a draw of its own from the root's uniform barycentric
                // coordinates (the loss, graying and shade draws would tie the lower
                // lashes to the last lost, the first gray or the darkest).
                lashes.retain(|l| (977.0 * (l.bary[0] + 3.1 * l.bary[1])).fract() < LOWER_SHARE);
                for l in &mut lashes {
                    l.length_mm *= LOWER_LENGTH;
                }
            } else {
                lashes = lower;
            }
            lashes.extend(open::margin_lashes(
                mesh,
                &balls,
                mm,
                seed,
                open::Lid::Upper,
            ));
        }
        Self {
            lashes,
            units_per_mm: 1.0 / (metres_per_unit * 1e3),
        }
    }

    /// Every lash placed (young: none lost).
    pub fn len(&self) -> usize {
        self.lashes.len()
    }

    pub fn is_empty(&self) -> bool {
        self.lashes.is_empty()
    }

    /// The lashes left at an age, with their curves: `factors` the aged colour's (the
    /// brows' gray fraction, and `contrast`, the curve of the face's hair aging), `shape`
    /// the head's displacement and displaced normals at that age (as for the brows).
    pub fn strands(
        &self,
        mesh: &Mesh,
        factors: &ColourFactors,
        shape: Option<(&[Vec3], &[Vec3])>,
    ) -> Vec<BrowStrand> {
        let (positions, normals) = (mesh.positions(), mesh.normals());
        let aged = factors.contrast.clamp(0.0, 1.0);
        let gray_fraction = GRAY_LAG * factors.brow_gray_fraction();
        self.lashes
            .iter()
            .filter(|l| l.loss_draw >= LOSS * aged)
            .map(|l| {
                let (root, normal) = rooted(positions, normals, shape, l.vertices, l.bary);
                let normal = l.out.unwrap_or(normal);
                let length = l.length_mm * (1.0 - SHORTENING * aged) * self.units_per_mm;
                // Down the lid, turned sideways by the fan, kept in its (aged) plane.
                let down = -l.up * l.fan.cos() + l.lateral * l.fan.sin();
                let down = (down - normal * down.dot(normal)).normalize_or_zero();
                let leaving = |e: f32| down * e.cos() + normal * e.sin();
                // A quadratic curve leaving the lid at `elevation` and arriving at the tip
                // turned [`CURL_DEG`] further out.
                let middle = root + leaving(l.elevation) * (0.5 * length);
                let curl = l.curl * (1.0 - UNCURL * aged);
                let tip = middle + leaving(l.elevation + curl) * (0.5 * length);
                let gray = smooth01((gray_fraction - l.gray_draw) / 0.08);
                BrowStrand {
                    root: root.to_array(),
                    gray,
                    middle: middle.to_array(),
                    shade: l.shade,
                    tip: tip.to_array(),
                    coverage: 1.0 - 0.25 * gray,
                }
            })
            .collect()
    }
}

/// A young lash's length at `s` along the eye, mm.
fn length_mm(s: f32) -> f32 {
    let [inner, longest, outer] = LENGTH_MM;
    if s < 0.6 {
        inner + (longest - inner) * smooth01(s / 0.6)
    } else {
        longest + (outer - longest) * smooth01((s - 0.6) / 0.4)
    }
}

/// The fringe's density along the eye, 0–1 of [`DENSITY_PER_CM2`]: sparse at the inner
/// corner, full from a fifth of the way out, fading over the last eighth.
fn density(s: f32) -> f32 {
    smooth01((s - SPAN.0) / 0.15) * (1.0 - smooth01((s - (SPAN.1 - 0.12)) / 0.12))
}

mod open;

#[cfg(test)]
pub(crate) use open::eyeballs;

#[cfg(test)]
mod tests;
