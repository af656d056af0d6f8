//! Landmarks found automatically: the template aligned to the head by a similarity,
//! refined by iterative closest points, then each template landmark refined locally and
//! carried onto the head's surface. No learned model: it needs the head upright and
//! facing +Z (the scene's axes) and its size within 2× of what its units say.
//!
//! 1. Starts: the template's top on the head's top, its cranium's box centre on the
//!    head's, at five scales around the one the units give (×0.5 … ×2).
//! 2. Each start is refined by a trimmed similarity ICP: template points (the head above
//!    the neck's cut) to their closest head points, the 20 % farthest pairs and pairs
//!    whose normals disagree left out. The start with the smallest median distance wins.
//! 3. The face alone (75 mm around the nose, facing forward) is aligned again from
//!    there, so the features set the fit rather than the cranium's shape.
//! 4. Each landmark: a patch of the template around it (25 mm) is moved onto the head by
//!    the same ICP, translation only, from the face's alignment (the top of the head and
//!    the ears from the whole head's).
//! 5. The pairs are made mirror images about the face's midline (its own mirror plane,
//!    refined on the head from the aligned template's x = 0 plane), the midline points
//!    put on it, and each is carried onto the head's surface (closest point).

use glam::Vec3;

use super::Template;
use super::bvh::Bvh;
use super::mirror::{self, Plane};
use super::similarity::Similarity;
use crate::base::error::Error;
use crate::head::landmarks::{Landmarks, NAMES};
use crate::head::mesh::Mesh;

/// Template points used by the global alignment (every k-th vertex above the neck).
const SAMPLES: usize = 3000;
/// Template points of the coarse alignments that find a head's axes.
const COARSE_SAMPLES: usize = 600;
/// ICP iterations of each start of the global search, on the coarse samples.
const START_ITERATIONS: usize = 20;
/// Below this height (template metres) the template is neck, which heads cut anywhere.
const NECK_CUT_Y_M: f32 = -0.11;
/// Radius of the face region aligned after the whole head, template metres.
const FACE_M: f32 = 0.075;
/// How far from a face point its mirror image's skin is looked for (template metres)
/// when the face's own mirror plane is found.
const MIRROR_REACH_M: f32 = 0.01;
/// The most face points the mirror plane is refined with.
const MIRROR_POINTS: usize = 4000;
/// Radius of the patch refined around each landmark, template metres.
const PATCH_M: f32 = 0.025;
/// A mesh whose skin's area-weighted mean normal is at least this long faces one way: a
/// face only (a mask: no back of the head, no ears, no neck). A whole head, closed round
/// the back, has a short one (its neck's cut leaves it open downward).
const FACE_ONLY_MEAN_NORMAL: f32 = 0.45;
/// A face-only mesh is at least this deep along the way it faces, in its largest extent
/// (a face mask ≈ 0.45; a flat patch of skin 0).
const FACE_ONLY_DEPTH: f32 = 0.2;
/// Radius of the template's face aligned to a face-only mesh, template metres: forehead
/// to chin, cheek to cheek.
const FACE_ONLY_M: f32 = 0.09;
/// The landmarks a face-only mesh has no place for.
const OFF_THE_FACE: [&str; 3] = ["vertex", "tragion_r", "tragion_l"];

/// What the automatic search found.
#[derive(Clone, Debug)]
pub struct Found {
    pub landmarks: Landmarks,
    /// The template's coordinates to the head's.
    pub alignment: Similarity,
    /// Median distance of the aligned template to the head, template mm.
    pub median_distance_mm: f32,
}

/// Finds `template`'s landmarks on `head` (in the head mesh's coordinates, +Y up, face
/// toward +Z), whose units are about `metres_per_unit`.
pub fn landmarks(head: &Mesh, template: &Template, metres_per_unit: f32) -> Result<Found, Error> {
    let fail = |message: String| Error::Fit { message };
    let Searched {
        positions: h_pos,
        bvh,
        normals,
    } = &searched(head);
    if bvh.is_empty() {
        return Err(fail(
            "the head has no skin triangle to look for landmarks on".into(),
        ));
    }
    if !(metres_per_unit > 0.0 && metres_per_unit.is_finite()) {
        return Err(fail(format!(
            "metres per unit {metres_per_unit} is not a size"
        )));
    }
    let t_pos = template.mesh.positions();
    let t_nrm = template.mesh.normals();
    let face_only = face_only(head).is_some();
    let samples = if face_only {
        template_face(template)
    } else {
        template_samples(template, SAMPLES)
    };

    // The starts compared coarsely (as when finding the axes), the best one refined
    // with every sample. A face-only mesh: the template's face on it, no cranium to
    // start from.
    let factors = [0.5, 0.71, 1.0, 1.41, 2.0];
    let coarse = if face_only {
        face_search(&samples, bvh, normals, h_pos, metres_per_unit, &factors)
    } else {
        global_search(
            &template_samples(template, COARSE_SAMPLES),
            t_pos,
            bvh,
            normals,
            h_pos,
            glam::Mat3::IDENTITY,
            metres_per_unit,
            &factors,
            START_ITERATIONS,
        )
    };
    let best = coarse
        .map(|(_, coarse)| {
            let (s, median) = icp(&samples, bvh, normals, coarse, 40, true);
            (median / s.scale, s)
        })
        .filter(|(median_m, _)| median_m.is_finite());
    let Some((median_m, alignment)) = best else {
        return Err(fail(
            "the template could not be aligned to the head (is it upright and facing +Z?)".into(),
        ));
    };
    // The face alone, from the whole head's alignment: the features (brows, eyes, nose,
    // mouth, chin) then set the fit, not the cranium's shape.
    let face_centre = match (
        template.landmarks.get("nasion"),
        template.landmarks.get("subnasale"),
    ) {
        (Some(a), Some(b)) => (a + b) * 0.5,
        _ => Vec3::new(0.0, -0.015, 0.1),
    };
    let face: Vec<(Vec3, Vec3)> = (0..t_pos.len())
        .filter(|&i| t_pos[i].distance(face_centre) < FACE_M && t_nrm[i].z > 0.2)
        .map(|i| (t_pos[i], t_nrm[i]))
        .collect();
    let head_alignment = alignment;
    let alignment = if face.len() >= 100 {
        icp(&face, bvh, normals, alignment, 40, true).0
    } else {
        alignment
    };
    let mut landmarks = Landmarks::default();
    for name in NAMES {
        let Some(l) = template.landmarks.get(name) else {
            continue;
        };
        if face_only && OFF_THE_FACE.contains(&name) {
            continue;
        }
        let patch: Vec<(Vec3, Vec3)> = (0..t_pos.len())
            .filter(|&i| t_pos[i].distance(l) < PATCH_M)
            .map(|i| (t_pos[i], t_nrm[i]))
            .collect();
        // The top of the head and the ears follow the cranium, the rest the face.
        let start = if matches!(name, "vertex" | "tragion_r" | "tragion_l") {
            head_alignment
        } else {
            alignment
        };
        let local = if patch.len() >= 8 {
            icp(&patch, bvh, normals, start, 15, false).0
        } else {
            start
        };
        landmarks.set(name, local.apply(l))?;
    }
    // Faces are close to symmetric: the pairs are made mirror images about the face's
    // midline plane, the midline points put on it; this halves the scatter of each side's
    // own refinement. The plane is the face's own ([`mirror::refine`] from the template's
    // x = 0 as aligned: on a symmetric head that one lay 1–2 mm to one side).
    let start = Plane {
        origin: alignment.apply(Vec3::ZERO),
        normal: alignment.turn(Vec3::X).normalize_or(Vec3::X),
    };
    let centre = alignment.apply(face_centre);
    let reach = MIRROR_REACH_M * alignment.scale;
    let near: Vec<Vec3> = h_pos
        .iter()
        .copied()
        .filter(|p| p.distance(centre) < FACE_M * alignment.scale)
        .collect();
    // Evenly taken, at most MIRROR_POINTS (a dense head's proxy has tens of thousands).
    let near: Vec<Vec3> = near
        .iter()
        .copied()
        .step_by((near.len() / MIRROR_POINTS).max(1))
        .collect();
    let (plane, _) = mirror::refine(&near, bvh, normals, start, reach);
    let mirror = |p: Vec3| plane.mirror(p);
    let mut symmetric = Landmarks::default();
    for name in NAMES {
        let Some(p) = landmarks.get(name) else {
            continue;
        };
        let q = if let Some(side) = name.strip_suffix("_r") {
            let other = landmarks.get(&format!("{side}_l"));
            other.map_or(p, |o| (p + mirror(o)) * 0.5)
        } else if let Some(side) = name.strip_suffix("_l") {
            let other = landmarks.get(&format!("{side}_r"));
            other.map_or(p, |o| mirror((o + mirror(p)) * 0.5))
        } else {
            plane.project(p)
        };
        let on_head = bvh.closest(q, f32::INFINITY).map_or(q, |hit| hit.point);
        symmetric.set(name, on_head)?;
    }
    let landmarks = symmetric;
    Ok(Found {
        landmarks,
        alignment,
        median_distance_mm: median_m * 1e3,
    })
}

/// Whether `head` is a face only (a mask: no back, ears, scalp or neck), and which way it
/// faces: its skin's area-weighted mean normal, when at least [`FACE_ONLY_MEAN_NORMAL`]
/// long (a whole head's, closed round the back, is short) and the mesh at least
/// [`FACE_ONLY_DEPTH`] deep along it (a flat patch is not a face).
pub fn face_only(head: &Mesh) -> Option<Vec3> {
    let p = head.positions();
    let mut sum = Vec3::ZERO;
    let mut area = 0.0f32;
    for t in head.skin_indices().chunks_exact(3) {
        let [a, b, c] = [t[0], t[1], t[2]].map(|i| p.get(i as usize).copied().unwrap_or_default());
        let n = (b - a).cross(c - a);
        sum += n;
        area += n.length();
    }
    let mean = sum / area.max(f32::MIN_POSITIVE);
    if mean.length() < FACE_ONLY_MEAN_NORMAL {
        return None;
    }
    // A face has depth (its nose before its cheeks, a mask 9 cm deep for 20 cm tall); a
    // flat patch of skin, which faces one way too, has none.
    let facing = mean.normalize();
    let skin: Vec<Vec3> = head
        .skin_indices()
        .iter()
        .filter_map(|&i| p.get(i as usize).copied())
        .collect();
    let (lo, hi) = skin
        .iter()
        .fold((f32::INFINITY, f32::NEG_INFINITY), |(lo, hi), q| {
            let d = q.dot(facing);
            (lo.min(d), hi.max(d))
        });
    let size = crate::head::mesh::Aabb::from_points(&skin)?
        .size()
        .max_element();
    (hi - lo >= FACE_ONLY_DEPTH * size).then_some(facing)
}

/// The template's face (front-facing points within [`FACE_ONLY_M`] of the middle of the
/// nose, not below the chin), what a face-only mesh is aligned with.
fn template_face(template: &Template) -> Vec<(Vec3, Vec3)> {
    let (t_pos, t_nrm) = (template.mesh.positions(), template.mesh.normals());
    let l = &template.landmarks;
    let centre = match (l.get("nasion"), l.get("subnasale")) {
        (Some(a), Some(b)) => (a + b) * 0.5,
        _ => Vec3::new(0.0, -0.015, 0.1),
    };
    let chin = l.get("pogonion").map_or(f32::NEG_INFINITY, |c| c.y - 0.01);
    let face: Vec<usize> = (0..t_pos.len())
        .filter(|&i| {
            t_pos[i].distance(centre) < FACE_ONLY_M && t_nrm[i].z > 0.2 && t_pos[i].y > chin
        })
        .collect();
    let step = (face.len() / SAMPLES).max(1);
    face.iter()
        .step_by(step)
        .map(|&i| (t_pos[i], t_nrm[i]))
        .collect()
}

/// [`global_search`] for a face-only mesh (+Y up, +Z forward): the template's face
/// `samples` started at each scale `factor` around `metres_per_unit` with the middle of
/// their box on the middle of the head's, its front on the head's front.
fn face_search(
    samples: &[(Vec3, Vec3)],
    bvh: &Bvh,
    normals: &[Vec3],
    h_pos: &[Vec3],
    metres_per_unit: f32,
    factors: &[f32],
) -> Option<(f32, Similarity)> {
    use rayon::prelude::*;
    let points: Vec<Vec3> = samples.iter().map(|s| s.0).collect();
    let t_box = crate::head::mesh::Aabb::from_points(&points)?;
    let h_box = crate::head::mesh::Aabb::from_points(h_pos)?;
    let tried: Vec<Option<(f32, Similarity)>> = factors
        .par_iter()
        .map(|&factor| {
            let scale = 1.0 / (metres_per_unit * factor);
            let (t_c, h_c) = (t_box.centre(), h_box.centre());
            let translation =
                Vec3::new(h_c.x, h_c.y, h_box.max.z) - Vec3::new(t_c.x, t_c.y, t_box.max.z) * scale;
            let start = Similarity {
                scale,
                rotation: glam::Quat::IDENTITY,
                translation,
            };
            let (s, median) = icp(samples, bvh, normals, start, START_ITERATIONS, true);
            let median_m = median / s.scale;
            median_m.is_finite().then_some((median_m, s))
        })
        .collect();
    best_start(tried)
}

/// The best similarity-ICP alignment of the template `samples` onto the head (its tree
/// and triangle normals in the file's coordinates) from starts at each scale `factor`
/// around `metres_per_unit`: the template's top on the head's top and its cranium's box
/// centre on the head's, seen in the frame `turn` takes the file's coordinates to
/// (+Y up, +Z forward). Returns the median distance (template metres) and the template's
/// coordinates to the head file's. Starts run side by side; the best is chosen in start
/// order (the same on any thread count).
#[allow(clippy::too_many_arguments)]
fn global_search(
    samples: &[(Vec3, Vec3)],
    t_pos: &[Vec3],
    bvh: &Bvh,
    normals: &[Vec3],
    h_pos: &[Vec3],
    turn: glam::Mat3,
    metres_per_unit: f32,
    factors: &[f32],
    iterations: usize,
) -> Option<(f32, Similarity)> {
    use rayon::prelude::*;
    let turned: Vec<Vec3> = h_pos.iter().map(|p| turn * *p).collect();
    let back = glam::Quat::from_mat3(&turn.transpose());
    let (h_top, t_top) = (top(&turned), top(t_pos));
    let tried: Vec<Option<(f32, Similarity)>> = factors
        .par_iter()
        .map(|&factor| {
            let scale = 1.0 / (metres_per_unit * factor);
            // The cranium: the 12 cm below the top, whose box centre is the skull's axis.
            let t_centre = band_centre(t_pos, t_top, 0.12)?;
            let h_centre = band_centre(&turned, h_top, 0.12 * scale)?;
            let translation = Vec3::new(h_centre.x, h_top, h_centre.z)
                - Vec3::new(t_centre.x, t_top, t_centre.z) * scale;
            // In the file's frame: turned back.
            let start = Similarity {
                scale,
                rotation: back,
                translation: back * translation,
            };
            let (s, median) = icp(samples, bvh, normals, start, iterations, true);
            let median_m = median / s.scale;
            median_m.is_finite().then_some((median_m, s))
        })
        .collect();
    best_start(tried)
}

/// Of the starts' results (median distance, alignment), in start order, the one with the
/// smallest median: the first of equals, so the same on any thread count.
fn best_start(tried: Vec<Option<(f32, Similarity)>>) -> Option<(f32, Similarity)> {
    let mut best: Option<(f32, Similarity)> = None;
    for (median_m, s) in tried.into_iter().flatten() {
        if best.as_ref().is_none_or(|b| median_m < b.0) {
            best = Some((median_m, s));
        }
    }
    best
}

/// The head file's up and forward axes found by aligning the template to it coarsely in
/// each of the 24 axis-aligned orientations (Y-up or Z-up, facing ±Z or ±Y, …): the one
/// the template fits best, with its median distance (template mm). agesim's own
/// (+Y up, +Z forward) is tried first and kept when the template fits it within
/// `good_mm`. `None` when the head has no skin.
pub fn axes(
    head: &Mesh,
    template: &Template,
    metres_per_unit: f32,
    good_mm: f32,
) -> Option<(crate::head::mesh::units::Axes, f32)> {
    use crate::head::mesh::units::{Axes, Axis};
    let Searched {
        positions: h_pos,
        bvh,
        normals,
    } = &searched(head);
    if bvh.is_empty() || !(metres_per_unit > 0.0 && metres_per_unit.is_finite()) {
        return None;
    }
    let t_pos = template.mesh.positions();
    let samples = template_samples(template, COARSE_SAMPLES);
    let all = Axis::ALL;
    let mut candidates = vec![Axes::STANDARD];
    for up in all {
        for forward in all {
            let a = Axes { up, forward };
            if a != Axes::STANDARD && a.to_standard().is_some() {
                candidates.push(a);
            }
        }
    }
    let mut best: Option<(Axes, f32)> = None;
    for axes in candidates {
        let Some(turn) = axes.to_standard() else {
            continue;
        };
        let Some((median_m, _)) = global_search(
            &samples,
            t_pos,
            bvh,
            normals,
            h_pos,
            turn,
            metres_per_unit,
            &[0.71, 1.0, 1.41],
            12,
        ) else {
            continue;
        };
        let mm = median_m * 1e3;
        if best.is_none_or(|b| mm < b.1) {
            best = Some((axes, mm));
        }
        if axes == Axes::STANDARD && mm <= good_mm {
            break;
        }
    }
    best
}

/// Trimmed ICP from `start`: a similarity (`similarity`), else a translation only.
/// Returns the result and its median pair distance (head units). Each iteration's
/// closest points are found in parallel, in the points' order (the same pairs, so the
/// same result, on any thread count): found one after the other they were most of the
/// serial time of opening a head.
fn icp(
    points: &[(Vec3, Vec3)],
    bvh: &Bvh,
    normals: &[Vec3],
    start: Similarity,
    iterations: usize,
    similarity: bool,
) -> (Similarity, f32) {
    let mut s = start;
    let mut median = f32::INFINITY;
    use rayon::prelude::*;
    for _ in 0..iterations {
        let mut pairs: Vec<(Vec3, Vec3, f32)> = points
            .par_iter()
            .with_min_len(64)
            .filter_map(|&(p, n)| {
                let q = s.apply(p);
                let hit = bvh.closest(q, f32::INFINITY)?;
                let facing = normals
                    .get(hit.triangle as usize)
                    .is_none_or(|hn| hn.dot(s.turn(n)) > 0.3);
                facing.then_some((p, hit.point, hit.distance))
            })
            .collect();
        if pairs.len() < 8 {
            break;
        }
        pairs.sort_by(|a, b| a.2.total_cmp(&b.2));
        median = pairs[pairs.len() / 2].2;
        pairs.truncate(pairs.len() * 4 / 5);
        let (from, to): (Vec<Vec3>, Vec<Vec3>) = pairs.iter().map(|p| (p.0, p.1)).unzip();
        let next = if similarity {
            match Similarity::fit(&from, &to, &[]) {
                Some(n) => n,
                None => break,
            }
        } else {
            let shift = from
                .iter()
                .zip(&to)
                .map(|(a, b)| *b - s.apply(*a))
                .sum::<Vec3>()
                / from.len() as f32;
            Similarity {
                translation: s.translation + shift,
                ..s
            }
        };
        let moved = next.translation.distance(s.translation);
        s = next;
        if moved < 1e-6 * s.scale {
            break;
        }
    }
    (s, median)
}

/// About `count` template points (with their normals) above the neck's cut, evenly
/// taken.
fn template_samples(template: &Template, count: usize) -> Vec<(Vec3, Vec3)> {
    let (t_pos, t_nrm) = (template.mesh.positions(), template.mesh.normals());
    let above: Vec<usize> = (0..t_pos.len())
        .filter(|&i| t_pos[i].y > NECK_CUT_Y_M)
        .collect();
    let step = (above.len() / count.max(1)).max(1);
    above
        .iter()
        .step_by(step)
        .map(|&i| (t_pos[i], t_nrm[i]))
        .collect()
}

fn top(points: &[Vec3]) -> f32 {
    points.iter().fold(f32::NEG_INFINITY, |m, p| m.max(p.y))
}

/// The centre of the box of the points within `depth` below `top`.
fn band_centre(points: &[Vec3], top: f32, depth: f32) -> Option<Vec3> {
    let band: Vec<Vec3> = points
        .iter()
        .copied()
        .filter(|p| p.y >= top - depth)
        .collect();
    crate::head::mesh::Aabb::from_points(&band).map(|b| b.centre())
}

/// The head's skin as the searches see it: its proxy when it is dense
/// ([`super::proxy::of_skin`]), with its tree and triangle normals.
struct Searched {
    positions: Vec<Vec3>,
    bvh: Bvh,
    normals: Vec<Vec3>,
}

fn searched(head: &Mesh) -> Searched {
    let skin = head.skin_indices();
    let (positions, indices) = match super::proxy::of_skin(head.positions(), &skin) {
        Some(p) => (p.positions, p.indices),
        None => (head.positions().to_vec(), skin.into_owned()),
    };
    Searched {
        bvh: Bvh::new(&positions, &indices),
        normals: triangle_normals(&positions, &indices),
        positions,
    }
}

fn triangle_normals(positions: &[Vec3], indices: &[u32]) -> Vec<Vec3> {
    indices
        .chunks_exact(3)
        .map(|t| {
            let p = |k: usize| positions.get(t[k] as usize).copied().unwrap_or(Vec3::ZERO);
            (p(1) - p(0)).cross(p(2) - p(0)).normalize_or_zero()
        })
        .collect()
}
