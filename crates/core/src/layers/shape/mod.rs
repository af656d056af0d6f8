//! Age changes the shape (docs/models.md §13 "Shape"): regions on the template, each a
//! smooth weight field with a displacement in millimetres — a descent along gravity, a
//! deflation along the inward normal, a bulge along the outward one — and its own age
//! curve. Read at each vertex's template point (the default head's own point, or the
//! fitted template's), so they reach any head; expressed in the head's own units.
//!
//! [`ShapeField::new`] computes every region's full (old-age) displacement per vertex once;
//! [`ShapeField::at`] weighs them by their curves at an age (a sum per vertex), and
//! [`ShapeField::normals`] gives the displaced mesh's normals (the original ones moved by
//! how the smooth normals of the displaced positions differ from the undisplaced: exactly
//! the original where nothing moves). Vertices at one position (split for UV seams) move
//! together; parts that are not skin (eyes, teeth) stay, but for their border where they
//! share a position with the skin (an eye socket's rim moves with the lid: no crack).

mod regions;
pub use regions::{BAGS, BROWS, LIDS, LIPS, REGIONS, drawn_crease};
mod roll;
use roll::DEPTH_GATE;
pub use roll::Roll;

use glam::Vec3;
use rayon::prelude::*;

use crate::age::{AgeCurve, CurveShape};
use crate::base::math::smoothstep;
use crate::head::frame::Regions;
use crate::head::mesh::Mesh;
use crate::head::mesh::normals::smooth_normals;
pub use basis::ShapeBasis;

/// How a region moves the skin.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Motion {
    /// Down along gravity (−Y of the scene: the head turned to agesim's axes).
    Descent,
    /// Inward along the normal (fat deflating, a hollow).
    Deflate,
    /// Outward along the normal (a bag, a jowl).
    Bulge,
    /// Back into the face (−Z of the scene, the head turned to agesim's axes), whichever
    /// way the skin faces: the lips as their support recedes, moving together so the
    /// slit between them stays closed.
    Retrude,
}

/// An ellipsoid of the face frame ([`Regions::relative`]: half the outer eye corners'
/// distance as the unit, the eye corners' midpoint as the origin), mirrored to both sides
/// when its centre is off the midline (what follows the template's own asymmetric folds is
/// a [`Roll`], one per side).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Blob {
    pub centre: [f32; 3],
    pub radii: [f32; 3],
    /// What this blob's bulge is, as a factor of its region's (1: the region's; 0.2 a
    /// fifth; 3 three times): a region whose parts descend alike but bulge differently.
    pub bulge: f32,
    /// The same for its descent (negative: it rises), its deflation and its retrusion.
    pub descent: f32,
    pub deflate: f32,
    pub retrude: f32,
    /// Whether its weight falls from its centre on (a dish), not from a plateau over its
    /// inner third (the plateau's rim draws a line where a hollow's slope ends).
    pub soft: bool,
}

impl Blob {
    const fn new(centre: [f32; 3], radii: [f32; 3]) -> Self {
        Self {
            centre,
            radii,
            bulge: 1.0,
            descent: 1.0,
            deflate: 1.0,
            retrude: 1.0,
            soft: false,
        }
    }

    /// The blob with `factor` times its region's bulge.
    const fn bulging(self, factor: f32) -> Self {
        Self {
            bulge: factor,
            ..self
        }
    }

    /// The blob as a dish: its weight falls from its centre on ([`Blob::soft`]).
    const fn soft(self) -> Self {
        Self { soft: true, ..self }
    }

    /// The blob with `factor` times its region's descent.
    const fn descending(self, factor: f32) -> Self {
        Self {
            descent: factor,
            ..self
        }
    }

    /// The blob with `factor` times its region's deflation.
    const fn deflating(self, factor: f32) -> Self {
        Self {
            deflate: factor,
            ..self
        }
    }

    /// The blob with `factor` times its region's retrusion.
    const fn retruding(self, factor: f32) -> Self {
        Self {
            retrude: factor,
            ..self
        }
    }

    /// 1 inside its inner third (at its centre when soft), falling smoothly to 0 at its
    /// surface.
    fn weight(&self, q: Vec3) -> f32 {
        let c = Vec3::from(self.centre);
        // Both sides: the x distance to the nearer of the centre and its mirror.
        let (q, c) = if c.x != 0.0 {
            (
                Vec3::new(q.x.abs(), q.y, q.z),
                Vec3::new(c.x.abs(), c.y, c.z),
            )
        } else {
            (q, c)
        };
        let d = ((q - c) / Vec3::from(self.radii)).length();
        let inner = if self.soft { 0.0 } else { 0.35 };
        1.0 - smoothstep(inner, 1.0, d)
    }
}

/// One shape region: where (the largest of its blobs' weights), how it moves (each motion
/// with its millimetres at full age and full strength) and when.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ShapeRegion {
    /// The project field of its strength (`shape.NAME`).
    pub name: &'static str,
    pub what: &'static str,
    pub blobs: &'static [Blob],
    pub motions: &'static [(Motion, f32)],
    /// Rolls of skin, each with its own millimetres (the region's motions move its blobs).
    pub rolls: &'static [Roll],
    pub curve: AgeCurve,
    /// Its share of the full move from [`crate::age::LATE_END_YEARS`] on
    /// (≥ 1; 1: it stops at its full move): [`regions::LATE_GAIN`] for volume and sag;
    /// 1 for the brows, lids, lips and nose, whose moves the clearance and the unfolding
    /// cut where the skin behind lies close or folds (a larger oldest move, cut, left
    /// them less moved at 80: the African woman's lips and nose, docs/models.md §13).
    pub late: f32,
}

impl ShapeRegion {
    /// Where it acts: the largest of its blobs' and rolls' weights.
    pub fn weight(&self, q: Vec3) -> f32 {
        self.rolls
            .iter()
            .map(|r| r.weight(q))
            .fold(self.blob_weight(q), f32::max)
    }

    /// Where its motions move the skin: the largest of its blobs' weights.
    pub fn blob_weight(&self, q: Vec3) -> f32 {
        self.blobs.iter().map(|b| b.weight(q)).fold(0.0, f32::max)
    }

    /// The weight of its bulge: the largest of its blobs' weights times their bulge
    /// factors.
    pub fn bulge_weight(&self, q: Vec3) -> f32 {
        self.blobs
            .iter()
            .map(|b| b.weight(q) * b.bulge)
            .fold(0.0, f32::max)
    }

    /// The weight of its descent, likewise (of the blobs' weighted descents, the one
    /// farthest from 0: a rising blob's negative one where it outweighs the others).
    pub fn descent_weight(&self, q: Vec3) -> f32 {
        self.blobs
            .iter()
            .map(|b| b.weight(q) * b.descent)
            .fold(0.0, mirrored::larger_magnitude)
    }

    /// The weight of its deflation, likewise.
    pub fn deflate_weight(&self, q: Vec3) -> f32 {
        self.blobs
            .iter()
            .map(|b| b.weight(q) * b.deflate)
            .fold(0.0, f32::max)
    }

    /// The weight of its retrusion, likewise.
    pub fn retrude_weight(&self, q: Vec3) -> f32 {
        self.blobs
            .iter()
            .map(|b| b.weight(q) * b.retrude)
            .fold(0.0, f32::max)
    }
}

use Motion::{Bulge, Deflate, Descent, Retrude};

/// Every region's full displacement per vertex of one head, in its units.
#[derive(Clone, Debug, PartialEq)]
pub struct ShapeField {
    /// Per region (in [`REGIONS`] order), per vertex.
    full: Vec<Vec<Vec3>>,
    /// Per region, per vertex: how far its deflation takes the vertex in at full age, mm
    /// (the hollow the region makes; a descent or a bulge makes none).
    hollow: Vec<Vec<f32>>,
    /// The smooth normals of the undisplaced positions, for [`ShapeField::normals`].
    smooth: Vec<Vec3>,
    /// The head's unit, metres.
    metres_per_unit: f32,
    /// The full shape's occlusion ratio per vertex, made at the first
    /// [`ShapeField::occlusion_at`].
    full_occlusion: std::sync::OnceLock<Vec<f32>>,
}

impl ShapeField {
    /// The regions' displacements on `mesh`: `template_point(v)` is vertex v's template
    /// point (template metres; `None`: off the template, it stays), `strengths` each
    /// region's multiplier (in [`REGIONS`] order), `metres_per_unit` the head's unit. Only
    /// skin vertices move.
    pub fn new(
        mesh: &Mesh,
        template_point: &dyn Fn(usize) -> Option<Vec3>,
        strengths: &[f32],
        metres_per_unit: f32,
    ) -> Self {
        Self::with_mirror(mesh, template_point, strengths, metres_per_unit, None)
    }

    /// [`ShapeField::new`], on a head whose outer eye corners are `eyes` (right, left; its
    /// units): where the head is its own mirror image about the plane between them, each
    /// region's move is made its mirror image too ([`symmetry::head_mirror`]) before the
    /// cuts, so a symmetric head ages alike on both sides (the regions lie on the
    /// template's points, and the template, a scan, is not quite symmetric: the African
    /// woman's lids and lips moved up to 3 mm differently on the two sides).
    pub fn with_mirror(
        mesh: &Mesh,
        template_point: &dyn Fn(usize) -> Option<Vec3>,
        strengths: &[f32],
        metres_per_unit: f32,
        eyes: Option<(Vec3, Vec3)>,
    ) -> Self {
        let basis = ShapeBasis::new(mesh, template_point, metres_per_unit, eyes);
        Self::on(mesh, &basis, strengths)
    }

    /// [`ShapeField::with_mirror`] on a [`ShapeBasis`] made of `mesh`: what a change of
    /// strengths makes again.
    pub fn on(mesh: &Mesh, basis: &ShapeBasis, strengths: &[f32]) -> Self {
        let n = mesh.vertex_count();
        let ShapeBasis {
            welded,
            skin,
            skin_at,
            points,
            smooth,
            own,
            mm,
            metres_per_unit,
            ..
        } = basis;
        let (mm, metres_per_unit) = (*mm, *metres_per_unit);
        let regions = Regions::template();
        let normals = mesh.normals();
        let (full, hollow) = REGIONS
            .iter()
            .enumerate()
            .map(|(r, region)| {
                let strength = strengths.get(r).copied().unwrap_or(1.0);
                if regions.is_none() || strength <= 0.0 {
                    return (vec![Vec3::ZERO; n], vec![0.0f32; n]);
                }
                let deflate_mm: f32 = region
                    .motions
                    .iter()
                    .filter(|(motion, _)| *motion == Deflate)
                    .map(|(_, amount)| amount)
                    .sum();
                let mut moved: Vec<(Vec3, f32)> = points
                    .par_iter()
                    .zip(skin_at)
                    .map(|(q, &s)| {
                        let Some(q) = *q else {
                            return (Vec3::ZERO, 0.0);
                        };
                        // Along the normal only where the skin faces out of the head (not
                        // the mouth's or the nostrils' inside: [`facing_out`]).
                        let facing = facing_out(q, normals[s as usize]);
                        let normal = normals[s as usize] * facing;
                        let rolled: f32 = region.rolls.iter().map(|r| r.height_mm(q)).sum();
                        let rolled = normal * (rolled * strength * mm);
                        let creased: f32 = region.rolls.iter().map(|r| r.hollow_mm(q)).sum();
                        let creased = creased * strength * facing;
                        let weight = region.blob_weight(q);
                        if weight <= 0.0 {
                            return (rolled, creased);
                        }
                        let bulge = region.bulge_weight(q) / weight;
                        let descent = region.descent_weight(q) / weight;
                        let deflate = region.deflate_weight(q) / weight;
                        let retrude = region.retrude_weight(q) / weight;
                        let d: Vec3 = region
                            .motions
                            .iter()
                            .map(|&(motion, amount)| {
                                amount
                                    * match motion {
                                        Descent => Vec3::NEG_Y * descent,
                                        Deflate => -normal * deflate,
                                        Bulge => normal * bulge,
                                        Retrude => Vec3::NEG_Z * retrude,
                                    }
                            })
                            .sum();
                        (
                            d * (weight * strength * mm) + rolled,
                            deflate_mm * deflate * weight * strength * facing + creased,
                        )
                    })
                    .collect();
                // The other vertices at a position (welded[v] < v) copy the first's,
                // whatever part they belong to.
                for v in 0..n {
                    let w = welded[v] as usize;
                    if w != v {
                        moved[v] = moved[w];
                    }
                }
                moved.into_iter().unzip()
            })
            .unzip();
        let mut full: Vec<Vec<Vec3>> = full;
        let mut hollow: Vec<Vec<f32>> = hollow;
        if let Some(own) = own {
            own.average(&mut full, &mut hollow, welded);
        }
        let (positions, indices) = (mesh.positions(), mesh.indices());
        // A dense head is settled on a coarser stand-in ([`coarse`]).
        if !coarse::settle(
            positions, indices, welded, skin, smooth, &mut full, points, mm,
        ) {
            settle::settle(
                positions,
                indices,
                welded,
                smooth,
                &mut full,
                points,
                mm,
                Some(basis.partners()),
            );
        }
        // The cuts, made vertex by vertex in turn, are not quite alike on the two sides of
        // a symmetric head (0.7 mm on the East Asian man): made mirror images once more.
        if let Some(own) = own {
            own.average(&mut full, &mut hollow, welded);
        }
        Self {
            full,
            hollow,
            smooth: smooth.clone(),
            metres_per_unit,
            full_occlusion: std::sync::OnceLock::new(),
        }
    }

    /// How much of the sky each vertex of `mesh` sees at `years` over how much it saw
    /// undisplaced (docs/models.md §13 "Occlusion"): what the skin pass multiplies the skin
    /// by. The full shape's ratio ([`occlusion::ratio`]), made once, toward 1 by
    /// [`Self::weight_at`] (exact young and at full age; between them the sky follows the
    /// movement's size). All 1 when nothing moves.
    pub fn occlusion_at(&self, mesh: &Mesh, years: f32) -> Vec<f32> {
        let n = mesh.vertex_count();
        let w = self.weight_at(years);
        if n != self.smooth.len() || w <= 0.0 {
            return vec![1.0; n];
        }
        let full = self.full_occlusion.get_or_init(|| {
            occlusion::full_ratio(
                mesh.positions(),
                &self.smooth,
                mesh.indices(),
                &self.full(),
                self.metres_per_unit,
            )
        });
        full.iter().map(|r| 1.0 + (r - 1.0) * w).collect()
    }

    /// Whether [`Self::occlusion_at`] at `years` on `mesh` measures nothing (the sky is
    /// measured already, or nothing moves there).
    pub fn occlusion_is_cheap(&self, mesh: &Mesh, years: f32) -> bool {
        self.full_occlusion.get().is_some()
            || mesh.vertex_count() != self.smooth.len()
            || self.weight_at(years) <= 0.0
    }

    /// How hollowed each vertex is at `years`, mm: the deflating regions' inward movement
    /// there (not a descent's or a bulge's), each times its share at that age
    /// ([`ShapeRegion::factor`]; docs/models.md §13 "Hollows").
    pub fn hollow_at(&self, years: f32) -> Vec<f32> {
        let n = self.smooth.len();
        let mut out = vec![0.0f32; n];
        for (field, region) in self.hollow.iter().zip(&REGIONS) {
            let f = region.factor(years);
            if f == 0.0 {
                continue;
            }
            for (o, h) in out.iter_mut().zip(field) {
                *o += h * f;
            }
        }
        out
    }

    /// This field with each region's moves and hollows scaled from the strengths `from`
    /// (the field's own) to `to`: what a shape slider shows while it moves (the moves are
    /// linear in the strengths; the settling that keeps the skin clear and unfolded is
    /// not, and is this field's, the still bake's is made afresh). `None` where a region
    /// is off in one and on in the other (nothing to scale).
    pub fn rescaled(&self, from: &[f32], to: &[f32]) -> Option<Self> {
        let ratio = |r: usize| {
            let (a, b) = (from.get(r).copied()?, to.get(r).copied()?);
            match (a > 0.0, b > 0.0) {
                (true, true) => Some(b / a),
                (false, false) => Some(0.0),
                _ => None,
            }
        };
        let ratios: Vec<f32> = (0..self.full.len()).map(ratio).collect::<Option<_>>()?;
        let scaled = |k: f32, v: &[Vec3]| v.iter().map(|d| *d * k).collect::<Vec<_>>();
        Some(Self {
            full: (self.full.iter().zip(&ratios))
                .map(|(f, &k)| scaled(k, f))
                .collect(),
            hollow: (self.hollow.iter().zip(&ratios))
                .map(|(h, &k)| h.iter().map(|x| x * k).collect())
                .collect(),
            smooth: self.smooth.clone(),
            metres_per_unit: self.metres_per_unit,
            full_occlusion: std::sync::OnceLock::new(),
        })
    }

    /// The displacement per vertex at `years`: each region's full displacement times its
    /// share there ([`ShapeRegion::factor`]: its curve, then the old age's gain).
    pub fn at(&self, years: f32) -> Vec<Vec3> {
        let factors: Vec<f32> = REGIONS.iter().map(|r| r.factor(years)).collect();
        self.weighted(&factors)
    }

    /// The oldest displacement: every region at its old-age share of its full move
    /// ([`ShapeRegion::oldest`]: the shape from 90 years on; the GLB's two morph targets
    /// at weight 1 each).
    pub fn full(&self) -> Vec<Vec3> {
        self.weighted(&ShapeRegion::oldest())
    }

    /// Σ factor_r · full_r.
    fn weighted(&self, factors: &[f32]) -> Vec<Vec3> {
        let n = self.smooth.len();
        let mut out = vec![Vec3::ZERO; n];
        for (field, &f) in self.full.iter().zip(factors) {
            if f == 0.0 {
                continue;
            }
            for (o, d) in out.iter_mut().zip(field) {
                *o += *d * f;
            }
        }
        out
    }

    /// How far toward [`Self::full`] the shape is at `years`: the displacement's size at
    /// that age over the oldest's (summed over the vertices; what the occlusion follows).
    pub fn weight_at(&self, years: f32) -> f32 {
        let full = size(&self.full());
        if full <= 0.0 {
            return 0.0;
        }
        (size(&self.at(years)) / full) as f32
    }

    /// The normals of `mesh` displaced by `delta`: each original normal turned by how the
    /// smooth normal there changes, so an undisplaced region keeps its normals exactly.
    pub fn normals(&self, mesh: &Mesh, delta: &[Vec3]) -> Vec<Vec3> {
        if delta.iter().all(|d| *d == Vec3::ZERO) {
            return mesh.normals().to_vec();
        }
        let moved: Vec<Vec3> = mesh
            .positions()
            .iter()
            .zip(delta)
            .map(|(p, d)| *p + *d)
            .collect();
        let smooth = smooth_normals(&moved, mesh.indices());
        mesh.normals()
            .iter()
            .zip(smooth.iter().zip(&self.smooth))
            .zip(delta)
            .map(|((n, (s, s0)), d)| {
                if *d == Vec3::ZERO && s == s0 {
                    *n
                } else {
                    (*n + (*s - *s0)).normalize_or(*n)
                }
            })
            .collect()
    }
}

/// A displacement's size: the sum of its vertices' moves (what a morph weight compares).
fn size(d: &[Vec3]) -> f64 {
    d.iter().map(|v| f64::from(v.length())).sum()
}

pub mod anatomy;
mod basis;
pub mod clearance;
mod coarse;
mod facing;
mod mirrored;
mod morph;
pub mod occlusion;
mod picture;
pub mod relief;
mod settle;
mod symmetry;
#[cfg(test)]
mod tests;
pub mod unfold;

pub use coarse::{COARSE_CUBE_MM, settles_on_stand_in};
pub use facing::{SKULL_CENTRE, facing_out};
pub use picture::{movement_mm, uv_picture};
