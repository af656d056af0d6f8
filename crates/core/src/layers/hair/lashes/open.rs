//! The lashes of an open eye (docs/models.md §9 "Eyelashes"). The template's eyes are
//! closed, and on a head with eyeballs its lids' slit falls near the lower lid's margin:
//! the lashes placed through the fit hung below it, and the upper lid had none (the open
//! eyes of the panel's heads read, blind, as "black slit eyes" with "floating lower
//! lashes"). Both margins are found on the head itself, where its skin meets the eyeball
//! in front of it.

use glam::Vec3;

use super::{FAN_CENTRE, FAN_DEG, Lash, length_mm};
use crate::head::mesh::Mesh;
use crate::layers::hair::brows::candidates;

/// Upper lashes per mm of the lid's margin (90–160 along about 30 mm, in two or three
/// rows); the lower lid's [`super::LOWER_SHARE`] of it.
const PER_MM: f32 = 4.0;

/// How far in front of the eyeball's centre, in its radius, the margin's skin lies (the
/// lids cover the ball's sides; the skin wrapping into the socket lies behind this).
const FRONT: f32 = 0.55;

/// How far off the ball's surface, in its radius, the margin's skin may lie.
const ON_BALL: (f32, f32) = (-0.06, 0.12);

/// The slices across the eye in which the margin is looked for, in the ball's radius.
const SLICE: f32 = 0.08;

/// A lash leaves the margin this far from the ball's forward direction at its root, away
/// from the eye's opening (up from the upper lid, down from the lower), and by its tip has
/// turned this much further, degrees: out over the eye, then curling away from it.
const LEAVING_DEG: f32 = 15.0;
const CURL_DEG: f32 = 35.0;

/// An upper lash's length, as a share of a closed lid's lash ([`length_mm`]): its root
/// hides under the lid's fold and only its outer part shows (at full length the open eyes'
/// fringe stood up off the lid like a false lash).
const LENGTH: f32 = 0.75;

/// The eyeballs of `mesh` (its parts [`crate::layers::skin_colour::is_eyeball`]): each
/// one's centre and radius. Their points are pooled and told apart by side (two eyes in
/// one part, or one part an eye).
pub(crate) fn eyeballs(mesh: &Mesh) -> Vec<(Vec3, f32)> {
    let positions = mesh.positions();
    let indices = mesh.indices();
    let mut vertices: Vec<u32> = Vec::new();
    for part in mesh.parts() {
        if !crate::layers::skin_colour::is_eyeball(part) {
            continue;
        }
        let first = part.first_triangle as usize * 3;
        let end = (first + part.triangle_count as usize * 3).min(indices.len());
        vertices.extend_from_slice(&indices[first.min(end)..end]);
    }
    vertices.sort_unstable();
    vertices.dedup();
    let ball = |of: &[Vec3]| -> Option<(Vec3, f32)> {
        if of.len() < 8 {
            return None;
        }
        let centre = of.iter().copied().sum::<Vec3>() / of.len() as f32;
        let radius = of.iter().map(|p| p.distance(centre)).sum::<f32>() / of.len() as f32;
        (radius > 0.0 && radius.is_finite()).then_some((centre, radius))
    };
    let points: Vec<Vec3> = vertices
        .iter()
        .filter_map(|&v| positions.get(v as usize).copied())
        .collect();
    let Some((centre, radius)) = ball(&points) else {
        return Vec::new();
    };
    // Two eyes: their points lie on two balls either side of the middle.
    let (left, right): (Vec<Vec3>, Vec<Vec3>) = points.iter().partition(|p| p.x < centre.x);
    match (ball(&left), ball(&right)) {
        (Some(l), Some(r)) if l.0.distance(r.0) > 1.5 * (l.1 + r.1) => vec![l, r],
        _ => vec![(centre, radius)],
    }
}

/// Which lid's margin.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(super) enum Lid {
    Upper,
    Lower,
}

/// The lashes of `lid` of each eyeball of `balls` (centre, radius) on `mesh`'s skin, `mm` a
/// millimetre in its units, deterministic in `seed`: along the lid's margin, the skin
/// nearest the eye's opening over the front of the ball (in each slice across the eye,
/// [`SLICE`] of the ball's radius wide, the skin vertex on the ball's surface above its
/// centre lowest, or below it highest), rooted between each two neighbouring margin
/// vertices. The lower lid's are fewer and shorter ([`super::LOWER_SHARE`],
/// [`super::LOWER_LENGTH`]).
pub(super) fn margin_lashes(
    mesh: &Mesh,
    balls: &[(Vec3, f32)],
    mm: f32,
    seed: u64,
    lid: Lid,
) -> Vec<Lash> {
    let (per_mm, length, up, sign) = match lid {
        Lid::Upper => (PER_MM, LENGTH, Vec3::NEG_Y, 1.0),
        Lid::Lower => (
            PER_MM * super::LOWER_SHARE,
            super::LOWER_LENGTH,
            Vec3::Y,
            -1.0,
        ),
    };
    let positions = mesh.positions();
    let mut on_skin = vec![false; positions.len()];
    for &v in mesh.skin_indices().iter() {
        on_skin[v as usize] = true;
    }
    let middle = balls.iter().map(|b| b.0.x).sum::<f32>() / balls.len().max(1) as f32;
    let mut lashes = Vec::new();
    for (e, &(centre, radius)) in balls.iter().enumerate() {
        // Toward the temple: away from the other eye (or from the head's middle).
        let outer = match (balls.len() > 1, centre.x >= middle, centre.x >= 0.0) {
            (true, true, _) | (false, _, true) => 1.0,
            _ => -1.0,
        };
        let slices = (2.0 / SLICE).ceil() as usize;
        let mut nearest: Vec<Option<(f32, u32)>> = vec![None; slices];
        for (v, p) in positions.iter().enumerate() {
            let d = *p - centre;
            let off = d.length() / radius - 1.0;
            // Height away from the centre, toward this lid.
            let height = sign * d.y;
            if !on_skin[v]
                || d.z <= FRONT * radius
                || !(ON_BALL.0..=ON_BALL.1).contains(&off)
                || height <= 0.0
            {
                continue;
            }
            let slice = (((d.x / radius + 1.0) / SLICE) as usize).min(slices - 1);
            if nearest[slice].is_none_or(|(h, _)| height < h) {
                nearest[slice] = Some((height, v as u32));
            }
        }
        let margin: Vec<u32> = nearest.iter().flatten().map(|&(_, v)| v).collect();
        for (k, pair) in margin.windows(2).enumerate() {
            let (a, b) = (pair[0], pair[1]);
            let (pa, pb) = (positions[a as usize], positions[b as usize]);
            // Neighbours only: no lashes across a gap in the margin.
            if pa.distance(pb) > 3.0 * SLICE * radius {
                continue;
            }
            let expected = pa.distance(pb) / mm * per_mm;
            let stream = (e * 1000 + k) as u64 + if lid == Lid::Lower { 500 } else { 0 };
            for (_, draws) in candidates::<7>(seed ^ 0x0be7_1a5e, stream, expected) {
                let u = draws[6];
                let root = pa.lerp(pb, u);
                // Along the eye, 0 at its inner corner and 1 at its outer.
                let s = (((root.x - centre.x) * outer / radius + 0.8) / 1.6).clamp(0.0, 1.0);
                let fan = FAN_DEG * (s - FAN_CENTRE) + (draws[1] - 0.5) * 16.0;
                lashes.push(Lash {
                    vertices: [a, b, a],
                    bary: [1.0 - u, u, 0.0],
                    lateral: Vec3::X * outer,
                    // The lash grows away from the opening (`strands` turns it from −up).
                    up,
                    fan: fan.to_radians(),
                    elevation: (90.0 - LEAVING_DEG + (draws[2] - 0.5) * 16.0).to_radians(),
                    curl: -CURL_DEG.to_radians(),
                    out: Some((root - centre).normalize_or_zero()),
                    length_mm: length * length_mm(s) * (0.8 + 0.4 * draws[3]),
                    loss_draw: draws[4],
                    gray_draw: draws[5],
                    shade: 0.7 + 0.3 * draws[0],
                });
            }
        }
    }
    lashes
}
