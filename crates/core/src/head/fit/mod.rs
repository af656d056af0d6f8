//! Any head: the template head fitted to an artist's head, and the correspondence every
//! layer is baked through (docs/models.md "Heads").
//!
//! The layout (wrinkle fibres, the wrinkle mask, the hair masks) is authored once on the
//! **template**, the default head, in its UV layout. For another head:
//!
//! 1. **Landmarks** on the head: the project's file (`mesh.landmarks`), else found
//!    automatically ([`auto::landmarks`]).
//! 2. **Similarity** (Umeyama): the head's landmarks onto the template's, least squares.
//! 3. **Thin-plate spline** from the similarity-aligned landmarks to the template's: the
//!    smoothest warp that puts each of the head's landmarks on the template's.
//! 4. **Non-rigid refinement** ([`refine`]): the warped skin drawn onto the template's
//!    surface by a smooth displacement field, in rounds of decreasing stiffness (non-rigid
//!    ICP), the landmarks anchored.
//! 5. **Closest point**: each warped vertex of the head's skin is projected onto the
//!    template surface ([`bvh::Bvh`]); its template UV is the layout there. Beyond
//!    [`MAX_DISTANCE_M`] (shoulders, a helmet, the inside of the mouth) it has none.
//!
//! The result, [`Fit`], holds a template UV for each head vertex. [`Correspondence`]
//! rasterises it in the head's own UV layout at a map size: for each texel, the template
//! UV the layers are read at (bilinear, the template's u wrapping at its back seam).
//! Texels just outside a UV island take their triangle's template UV extrapolated (1.5 px),
//! the rest their nearest written texel's (padding to the edges of the map), so filtering
//! and mip levels never pull in background, and the heights on both sides of a UV seam,
//! being one 3D point, agree.

pub mod auto;
pub mod bvh;
mod correspondence;
pub mod mirror;
pub mod proxy;
pub mod refine;
pub mod similarity;
pub mod tps;

use std::sync::{Arc, OnceLock};

use glam::{Vec2, Vec3};

pub use correspondence::{Correspondence, pad};

use crate::base::error::Error;
use crate::head::landmarks::Landmarks;
use crate::head::mesh::Mesh;
use bvh::Bvh;
use similarity::Similarity;
use tps::ThinPlate;

/// The template's landmarks: `assets/meshes/default-head.landmarks.json`, in the default
/// head's coordinates (metres, +Y up, face toward +Z).
pub const TEMPLATE_LANDMARKS_JSON: &str =
    include_str!("../../../../../assets/meshes/default-head.landmarks.json");

/// How far (template metres) a warped head point may be from the template surface and
/// still take its layout.
pub const MAX_DISTANCE_M: f32 = 0.02;

/// The smoothing of the landmark warp, metres: hand-placed landmarks are 2–3 mm off.
const TPS_LAMBDA_M: f32 = 0.002;

/// Fewest landmarks the fit works from (the similarity needs three; the warp four).
pub const MIN_LANDMARKS: usize = 5;

/// Twice the UV area below which a template triangle has no layout to read.
const MIN_UV_AREA: f32 = 1e-9;

/// The head every layout is authored on, with its landmarks and a tree for closest points.
#[derive(Debug)]
pub struct Template {
    pub mesh: Arc<Mesh>,
    pub landmarks: Landmarks,
    pub(crate) bvh: Bvh,
    /// The triangles of [`Template::bvh`] (its hits' `triangle` index these).
    bvh_indices: Vec<u32>,
    /// The unit normal of each of those triangles.
    bvh_normals: Vec<Vec3>,
    /// Metres per UV unit over its face (mean of u and v; `mesh::SurfaceScale::measure_face`).
    pub metres_per_uv: Option<f32>,
}

impl Template {
    /// Builds a template from a mesh in metres with its landmarks.
    pub fn new(mesh: Arc<Mesh>, landmarks: Landmarks) -> Self {
        // Triangles without UV area carry no layout (the scan's eye patches are joined to
        // the lids by such triangles, their rims collapsed to one UV): a closest point on
        // one would read that one UV for a whole rim.
        let uvs = mesh.uvs();
        let with_area: Vec<u32> = mesh
            .skin_indices()
            .chunks_exact(3)
            .filter(|t| {
                let [a, b, c] = [t[0], t[1], t[2]].map(|i| uvs[i as usize]);
                (b - a).perp_dot(c - a).abs() > MIN_UV_AREA
            })
            .flatten()
            .copied()
            .collect();
        let bvh = Bvh::new(mesh.positions(), &with_area);
        let p = mesh.positions();
        let bvh_normals = with_area
            .chunks_exact(3)
            .map(|t| {
                let [a, b, c] = [t[0], t[1], t[2]].map(|i| p[i as usize]);
                (b - a).cross(c - a).normalize_or_zero()
            })
            .collect();
        let bvh_indices = with_area;
        let metres_per_uv = crate::head::mesh::SurfaceScale::measure_face(&mesh, Some(&landmarks))
            .map(|s| 0.5 * (s.units_per_u + s.units_per_v));
        Self {
            mesh,
            landmarks,
            bvh,
            bvh_indices,
            bvh_normals,
            metres_per_uv,
        }
    }

    /// The template UV at a closest-point hit.
    fn uv_at(&self, hit: &bvh::Hit) -> Vec2 {
        let t = hit.triangle as usize * 3;
        let idx = &self.bvh_indices;
        let uvs = self.mesh.uvs();
        let uv = |k: usize| uvs[idx[t + k] as usize];
        let (a, b, c) = (uv(0), uv(1), uv(2));
        // The default head's u wraps at its back seam: unwrap before interpolating.
        let (a, b, c) = unwrap_u([a, b, c]);
        let p = a * hit.bary.x + b * hit.bary.y + c * hit.bary.z;
        Vec2::new(p.x.rem_euclid(1.0), p.y)
    }
}

/// The built-in template: the default head and its landmark file (built once).
pub fn template() -> &'static Template {
    static TEMPLATE: OnceLock<Template> = OnceLock::new();
    TEMPLATE.get_or_init(|| {
        // The built-in file is checked by the tests; an unreadable one leaves no landmark
        // (every fit then says so) rather than a panic.
        let landmarks = Landmarks::from_json_str(TEMPLATE_LANDMARKS_JSON).unwrap_or_default();
        Template::new(Arc::new(crate::head::default::default_head()), landmarks)
    })
}

/// The head's layout on the template: a template UV per head vertex.
#[derive(Clone, Debug)]
pub struct Fit {
    /// Per vertex of the head: the template UV, `None` beyond [`MAX_DISTANCE_M`] or off
    /// the skin.
    pub template_uv: Vec<Option<Vec2>>,
    /// Per vertex of the head: the template surface point (template metres) its UV is
    /// read at, `None` where the UV is. The colour's regions and the brows read it.
    pub template_point: Vec<Option<Vec3>>,
    /// Per vertex of the head: the warped and refined point the surface point was found
    /// from (template metres, within a millimetre or two of the surface), `None` where the
    /// UV is: what the shape's regions and rolls read. A smooth field's, it folds nowhere;
    /// the closest surface point leaps across the template's deep creases (the nasolabial
    /// folds), folding the head's triangles over on the template, where the cheek's roll
    /// then drew a crack. (The colour's regions keep the surface point: its leaps keep a
    /// nostril's inside off the cheeks the skin tone is measured on.)
    pub refined_point: Vec<Option<Vec3>>,
    /// The head's coordinates to the template's.
    pub similarity: Similarity,
    /// What the fit found, for reports.
    pub report: FitReport,
}

/// What a fit used and how well it went.
#[derive(Clone, Debug, PartialEq)]
pub struct FitReport {
    /// Landmarks both heads have.
    pub landmarks_used: usize,
    /// Mean distance of the similarity-aligned landmarks to the template's, template mm
    /// (before the warp, which puts them on).
    pub similarity_residual_mm: f32,
    /// Skin vertices that found a template point.
    pub matched_vertices: usize,
    pub skin_vertices: usize,
    /// The non-rigid refinement after the warp (`None`: not run).
    pub refined: Option<refine::RefineReport>,
}

impl std::fmt::Display for FitReport {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(
            f,
            "{} landmarks, {:.1} mm apart after the similarity; ",
            self.landmarks_used, self.similarity_residual_mm,
        )?;
        if let Some(r) = &self.refined {
            write!(
                f,
                "skin {:.1} mm from the template after the warp, {:.1} mm refined (median); ",
                r.median_before_mm, r.median_after_mm
            )?;
        }
        write!(
            f,
            "{} of {} skin vertices on the template",
            self.matched_vertices, self.skin_vertices
        )
    }
}

/// How a fit is made.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct FitOptions {
    /// Rounds of [`refine::SCHEDULE`] the landmark warp is refined by (non-rigid ICP,
    /// [`refine`]); 0: none.
    pub refine_rounds: usize,
}

impl Default for FitOptions {
    fn default() -> Self {
        Self {
            refine_rounds: refine::SCHEDULE.len(),
        }
    }
}

/// Fits `template` to `head`, whose `landmarks` are in the head mesh's coordinates (the
/// scene's: turned to +Y up, +Z forward).
pub fn fit(head: &Mesh, landmarks: &Landmarks, template: &Template) -> Result<Fit, Error> {
    fit_with(head, landmarks, template, FitOptions::default())
}

/// [`fit`] with `options`.
pub fn fit_with(
    head: &Mesh,
    landmarks: &Landmarks,
    template: &Template,
    options: FitOptions,
) -> Result<Fit, Error> {
    let (from, to): (Vec<Vec3>, Vec<Vec3>) = crate::head::landmarks::NAMES
        .iter()
        .filter_map(|n| Some((landmarks.get(n)?, template.landmarks.get(n)?)))
        .unzip();
    let fail = |message: String| Error::Fit { message };
    if from.len() < MIN_LANDMARKS {
        return Err(fail(format!(
            "{} landmarks placed; the fit needs at least {MIN_LANDMARKS} (the eye corners, the nose tip, the mouth corners…)",
            from.len()
        )));
    }
    let similarity = Similarity::fit(&from, &to, &[])
        .ok_or_else(|| fail("the landmarks are all at one point: place them on the face".into()))?;
    let aligned: Vec<Vec3> = from.iter().map(|&p| similarity.apply(p)).collect();
    let residual = aligned
        .iter()
        .zip(&to)
        .map(|(a, b)| a.distance(*b))
        .sum::<f32>()
        / from.len() as f32;
    // Landmarks on one plane (a face mask's five front points) leave the warp undefined:
    // the similarity alone then carries the head.
    let warp = ThinPlate::fit(&aligned, &to, TPS_LAMBDA_M);
    let positions = head.positions();
    let mut skin = vec![false; positions.len()];
    for &i in head.skin_indices().iter() {
        if let Some(s) = skin.get_mut(i as usize) {
            *s = true;
        }
    }
    use rayon::prelude::*;
    // The skin warped into the template's space, refined onto its surface.
    let skin_vertices: Vec<usize> = (0..positions.len()).filter(|&i| skin[i]).collect();
    let warped = |p: Vec3| {
        let q = similarity.apply(p);
        warp.as_ref().map_or(q, |w| w.apply(q))
    };
    let mut points: Vec<Vec3> = skin_vertices
        .par_iter()
        .map(|&i| warped(positions[i]))
        .collect();
    let rounds = &refine::SCHEDULE[..options.refine_rounds.min(refine::SCHEDULE.len())];
    let refined = (!rounds.is_empty()).then(|| {
        let normals: Vec<Vec3> = skin_vertices
            .iter()
            .map(|&i| similarity.turn(head.normals()[i]).normalize_or_zero())
            .collect();
        let anchors: Vec<Vec3> = from.iter().map(|&p| warped(p)).collect();
        refine::refine(
            &mut points,
            &normals,
            &template.bvh,
            &template.bvh_normals,
            &anchors,
            rounds,
        )
    });
    let hits: Vec<Option<bvh::Hit>> = points
        .par_iter()
        .map(|&q| template.bvh.closest(q, MAX_DISTANCE_M))
        .collect();
    let mut template_uv = vec![None; positions.len()];
    let mut template_point = vec![None; positions.len()];
    let mut refined_point = vec![None; positions.len()];
    for ((&i, hit), point) in skin_vertices.iter().zip(&hits).zip(&points) {
        if let Some(hit) = hit {
            template_uv[i] = Some(template.uv_at(hit));
            template_point[i] = Some(hit.point);
            refined_point[i] = Some(*point);
        }
    }
    let report = FitReport {
        landmarks_used: from.len(),
        similarity_residual_mm: residual * 1e3,
        matched_vertices: template_uv.iter().filter(|t| t.is_some()).count(),
        skin_vertices: skin_vertices.len(),
        refined,
    };
    if report.matched_vertices == 0 {
        return Err(fail(format!(
            "no point of the head came within {} mm of the template ({report}): are the landmarks on this head?",
            MAX_DISTANCE_M * 1e3
        )));
    }
    Ok(Fit {
        template_uv,
        template_point,
        refined_point,
        similarity,
        report,
    })
}

/// Three UVs with u unwrapped across the template's back seam (u = 0 ≡ 1): when they
/// span more than half the chart, the small ones are taken one turn on.
pub(crate) fn unwrap_u(uv: [Vec2; 3]) -> (Vec2, Vec2, Vec2) {
    let (lo, hi) = uv
        .iter()
        .fold((f32::INFINITY, f32::NEG_INFINITY), |(l, h), p| {
            (l.min(p.x), h.max(p.x))
        });
    let fix = |p: Vec2| {
        if hi - lo > 0.5 && p.x < 0.5 {
            Vec2::new(p.x + 1.0, p.y)
        } else {
            p
        }
    };
    (fix(uv[0]), fix(uv[1]), fix(uv[2]))
}

#[cfg(test)]
mod tests;
