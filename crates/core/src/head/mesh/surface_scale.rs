//! How long one UV unit is on a surface: the measured UV density that puts the repeated
//! tiles (micro-relief, fine wrinkles) at their physical size, shared by the renderer and
//! the exported normal map (docs/models.md "Rendering").

use glam::{Vec2, Vec3};
use rayon::prelude::*;

/// Fewest triangles [`SurfaceScale::measure_face`] measures the face over.
const MIN_FACE_TRIANGLES: usize = 20;

/// How long one UV unit is on the surface, along u and along v, in mesh units: the
/// area-weighted median of |∂P/∂u| and |∂P/∂v| over the triangles (the tangent-frame
/// derivatives of docs/models.md §5). With the mesh's metres per unit it says how many times a
/// tile of a given physical size repeats across the UV square.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct SurfaceScale {
    /// Mesh units per UV unit along u.
    pub units_per_u: f32,
    /// Mesh units per UV unit along v.
    pub units_per_v: f32,
}

impl SurfaceScale {
    /// Measures `mesh`; triangles with degenerate UVs are skipped. `None` when every
    /// triangle is degenerate.
    pub fn measure(positions: &[Vec3], uvs: &[Vec2], indices: &[u32]) -> Option<Self> {
        // (|∂P/∂u|, |∂P/∂v|, area) per triangle, in the triangles' order.
        let per: Vec<(f32, f32, f32)> = indices
            .par_chunks_exact(3)
            .with_min_len(4096)
            .filter_map(|tri| {
                let [a, b, c] = [tri[0] as usize, tri[1] as usize, tri[2] as usize];
                let (e1, e2) = (positions[b] - positions[a], positions[c] - positions[a]);
                let (d1, d2) = (uvs[b] - uvs[a], uvs[c] - uvs[a]);
                let det = d1.x * d2.y - d2.x * d1.y;
                let area = 0.5 * e1.cross(e2).length();
                if det.abs() < 1e-12 || area <= 0.0 || !area.is_finite() {
                    return None;
                }
                // Solve [e1 e2] = [dP/du dP/dv]·[d1 d2] (Lengyel's tangent derivation).
                let dp_du = (e1 * d2.y - e2 * d1.y) / det;
                let dp_dv = (e2 * d1.x - e1 * d2.x) / det;
                (dp_du.is_finite() && dp_dv.is_finite())
                    .then(|| (dp_du.length(), dp_dv.length(), area))
            })
            .collect();
        if per.is_empty() {
            return None;
        }
        let (units_per_u, units_per_v) = rayon::join(
            || weighted_median(per.iter().map(|p| (p.0, p.2)).collect()),
            || weighted_median(per.iter().map(|p| (p.1, p.2)).collect()),
        );
        Some(Self {
            units_per_u,
            units_per_v,
        })
    }

    /// [`SurfaceScale::measure`] over the face of `mesh`'s skin: the triangles within one
    /// outer-eye-corner distance of the middle of the face (the eye corners and the base
    /// of the nose, `landmarks` in the mesh's units), where wrinkles and pores are looked
    /// at. A layout may give the face more of the UV square than the scalp and neck (the
    /// default head's: ≈ 3× denser there), so a tile sized by the whole surface would be
    /// the wrong size on the face. Without those landmarks, or with too few triangles
    /// there, the whole skin.
    pub fn measure_face(
        mesh: &super::Mesh,
        landmarks: Option<&crate::head::landmarks::Landmarks>,
    ) -> Option<Self> {
        let skin = mesh.skin_indices();
        let face = landmarks.and_then(|l| {
            let eyes = l.exocanthion_distance()?;
            let centre =
                (l.get("exocanthion_r")? + l.get("exocanthion_l")? + l.get("subnasale")?) / 3.0;
            let p = mesh.positions();
            let near: Vec<u32> = skin
                .chunks_exact(3)
                .filter(|t| {
                    let c = (p[t[0] as usize] + p[t[1] as usize] + p[t[2] as usize]) / 3.0;
                    c.distance(centre) <= eyes
                })
                .flatten()
                .copied()
                .collect();
            (near.len() >= 3 * MIN_FACE_TRIANGLES).then_some(near)
        });
        Self::measure(
            mesh.positions(),
            mesh.uvs(),
            face.as_deref().unwrap_or(&skin),
        )
    }

    /// Whole repeats of a tile `tile_size_m` on a side across the UV square: rounded to
    /// an integer (at least 1) so the tile wraps seamlessly across the UV seam.
    pub fn repeats(&self, metres_per_unit: f32, tile_size_m: f32) -> [f32; 2] {
        let per = |units: f32| ((units * metres_per_unit / tile_size_m).round()).max(1.0);
        [per(self.units_per_u), per(self.units_per_v)]
    }
}

/// The value below which half the weight lies (`(value, weight)` pairs, weights > 0): a
/// few triangles whose UVs are squeezed to a point (a scan's eyelid rim) do not move it,
/// as they would an area-weighted mean.
fn weighted_median(mut values: Vec<(f32, f32)>) -> f32 {
    // Stable, so the same order as a serial sort (a dense head's 570k triangles: a fifth of
    // a second on one core).
    values.par_sort_by(|a, b| a.0.total_cmp(&b.0));
    let half = 0.5 * values.iter().map(|v| f64::from(v.1)).sum::<f64>();
    let mut below = 0.0f64;
    for &(value, weight) in &values {
        below += f64::from(weight);
        if below >= half {
            return value;
        }
    }
    values.last().map_or(0.0, |v| v.0)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn quad() -> (Vec<Vec3>, Vec<Vec2>, Vec<u32>) {
        // 0.2 × 0.1 units, UV 0..1 both ways.
        let p = vec![
            Vec3::new(0.0, 0.0, 0.0),
            Vec3::new(0.2, 0.0, 0.0),
            Vec3::new(0.2, 0.1, 0.0),
            Vec3::new(0.0, 0.1, 0.0),
        ];
        let uv = vec![
            Vec2::new(0.0, 0.0),
            Vec2::new(1.0, 0.0),
            Vec2::new(1.0, 1.0),
            Vec2::new(0.0, 1.0),
        ];
        (p, uv, vec![0, 1, 2, 0, 2, 3])
    }

    #[test]
    fn scale_of_a_stretched_quad() {
        let (p, uv, idx) = quad();
        let s = SurfaceScale::measure(&p, &uv, &idx).unwrap();
        assert!((s.units_per_u - 0.2).abs() < 1e-6, "{s:?}");
        assert!((s.units_per_v - 0.1).abs() < 1e-6, "{s:?}");
        // 0.2 m / 0.05 m = 4 repeats in u, 2 in v.
        assert_eq!(s.repeats(1.0, 0.05), [4.0, 2.0]);
        // Never fewer than one repeat.
        assert_eq!(s.repeats(1.0, 10.0), [1.0, 1.0]);
    }
}
