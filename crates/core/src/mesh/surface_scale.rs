//! How long one UV unit is on a surface: the measured UV density that puts the repeated
//! tiles (micro-relief, fine wrinkles) at their physical size, shared by the renderer and
//! the exported normal map (docs/models.md "Rendering").

use glam::{Vec2, Vec3};

/// How long one UV unit is on the surface, along u and along v, in mesh units: the
/// area-weighted mean of |∂P/∂u| and |∂P/∂v| over the triangles (the tangent-frame
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
        let mut sum = [0.0f64; 2];
        let mut area_sum = 0.0f64;
        for tri in indices.chunks_exact(3) {
            let [a, b, c] = [tri[0] as usize, tri[1] as usize, tri[2] as usize];
            let (e1, e2) = (positions[b] - positions[a], positions[c] - positions[a]);
            let (d1, d2) = (uvs[b] - uvs[a], uvs[c] - uvs[a]);
            let det = d1.x * d2.y - d2.x * d1.y;
            let area = 0.5 * e1.cross(e2).length();
            if det.abs() < 1e-12 || area <= 0.0 || !area.is_finite() {
                continue;
            }
            // Solve [e1 e2] = [dP/du dP/dv]·[d1 d2] (Lengyel's tangent derivation).
            let dp_du = (e1 * d2.y - e2 * d1.y) / det;
            let dp_dv = (e2 * d1.x - e1 * d2.x) / det;
            if !(dp_du.is_finite() && dp_dv.is_finite()) {
                continue;
            }
            sum[0] += f64::from(dp_du.length()) * f64::from(area);
            sum[1] += f64::from(dp_dv.length()) * f64::from(area);
            area_sum += f64::from(area);
        }
        (area_sum > 0.0).then(|| Self {
            units_per_u: (sum[0] / area_sum) as f32,
            units_per_v: (sum[1] / area_sum) as f32,
        })
    }

    /// Whole repeats of a tile `tile_size_m` on a side across the UV square: rounded to
    /// an integer (at least 1) so the tile wraps seamlessly across the UV seam.
    pub fn repeats(&self, metres_per_unit: f32, tile_size_m: f32) -> [f32; 2] {
        let per = |units: f32| ((units * metres_per_unit / tile_size_m).round()).max(1.0);
        [per(self.units_per_u), per(self.units_per_v)]
    }
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
