//! The shape's cuts alike on both sides of the face (docs/models.md §13 "Alike on both
//! sides"). Keeping the skin clear of the skin and unfolding it shorten a move where the
//! head's own triangles would fold or cross; a head is never quite symmetric, so one side
//! was cut more than the other: on the African woman one upper lid came down half as far
//! as the other, read blind as "one half-closed eye, like ptosis or an injury". Each
//! vertex's move is shortened to the share its mirror image keeps, when that is less.

use std::collections::HashMap;

use glam::Vec3;

/// Each point's mirror partner: the point nearest its mirror image about x = 0 (face
/// units, [`crate::head::frame::Regions::relative`]) within `tolerance`; `None` for no
/// point, or none near enough.
pub fn mirror_partners(points: &[Option<Vec3>], tolerance: f32) -> Vec<Option<u32>> {
    let cell = tolerance.max(1e-6);
    let key = |p: Vec3| (p / cell).floor().as_ivec3().to_array();
    let mut grid: HashMap<[i32; 3], Vec<u32>> = HashMap::new();
    for (i, p) in points.iter().enumerate() {
        if let Some(p) = p {
            grid.entry(key(*p)).or_default().push(i as u32);
        }
    }
    points
        .iter()
        .map(|p| {
            let mirrored = (*p)? * Vec3::new(-1.0, 1.0, 1.0);
            let [x, y, z] = key(mirrored);
            let mut best: Option<(f32, u32)> = None;
            for dx in -1..=1 {
                for dy in -1..=1 {
                    for dz in -1..=1 {
                        let Some(list) = grid.get(&[x + dx, y + dy, z + dz]) else {
                            continue;
                        };
                        for &j in list {
                            let d = points[j as usize]
                                .map_or(f32::INFINITY, |q| q.distance_squared(mirrored));
                            if d <= tolerance * tolerance && best.is_none_or(|(b, _)| d < b) {
                                best = Some((d, j));
                            }
                        }
                    }
                }
            }
            best.map(|(_, j)| j)
        })
        .collect()
}

/// Shortens each vertex's move (all regions' displacements `full`, per region per vertex)
/// to the share of its uncut move (`uncut`, the sum over the regions before the cuts)
/// that its mirror partner keeps, when that is less than its own share. Vertices without
/// a partner keep theirs. Returns how many were shortened.
pub fn even_out(full: &mut [Vec<Vec3>], uncut: &[Vec3], partners: &[Option<u32>]) -> usize {
    let n = uncut.len();
    let kept = |v: usize, full: &[Vec<Vec3>]| {
        let before = uncut[v].length();
        if before <= 1e-12 {
            return 1.0;
        }
        let after: Vec3 = full.iter().map(|f| f[v]).sum();
        (after.length() / before).min(1.0)
    };
    let shares: Vec<f32> = (0..n).map(|v| kept(v, full)).collect();
    let mut shortened = 0;
    for v in 0..n {
        let Some(p) = partners[v] else {
            continue;
        };
        let (own, other) = (shares[v], shares[p as usize]);
        if other < own - 1e-3 && own > 0.0 {
            let scale = other / own;
            for f in full.iter_mut() {
                f[v] *= scale;
            }
            shortened += 1;
        }
    }
    shortened
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn partners_are_mirror_images_within_the_tolerance() {
        let points = vec![
            Some(Vec3::new(0.5, 0.1, 0.2)),
            Some(Vec3::new(-0.51, 0.1, 0.2)),
            Some(Vec3::new(0.9, 0.0, 0.0)),
            None,
            Some(Vec3::new(0.0, 1.0, 0.0)),
        ];
        let p = mirror_partners(&points, 0.05);
        assert_eq!(p, vec![Some(1), Some(0), None, None, Some(4)]);
    }

    #[test]
    fn the_side_cut_less_is_cut_as_much_as_its_mirror_image() {
        // Two vertices, one region; the first kept half its move, the second all of it.
        let uncut = vec![Vec3::new(0.0, -2.0, 0.0), Vec3::new(0.0, -2.0, 0.0)];
        let mut full = vec![vec![Vec3::new(0.0, -1.0, 0.0), Vec3::new(0.0, -2.0, 0.0)]];
        let partners = vec![Some(1), Some(0)];
        assert_eq!(even_out(&mut full, &uncut, &partners), 1);
        assert_eq!(full[0], vec![Vec3::new(0.0, -1.0, 0.0); 2]);
        // Alike already: nothing to do.
        assert_eq!(even_out(&mut full, &uncut, &partners), 0);
    }
}
