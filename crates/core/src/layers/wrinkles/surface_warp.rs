//! A wrinkle group laid straight on the head's surface instead of in its UV layout
//! (docs/models.md §3, the `space=surface` key).
//!
//! A UV layout is affine on each triangle, and the affine maps of neighbouring triangles
//! differ: a line straight in UV bends on the surface at every edge it crosses. Over a
//! scanned head's 5 mm triangles a fan of lines drawn straight in UV reads as wavy,
//! stacked ripples. A warp gives each texel near the group the UV point it would have if
//! the layout there were one affine map: its surface point, projected on the surface's
//! tangent plane, through the affine map that best fits the layout over the group
//! (least squares). The group's wrinkles are evaluated at the warped points, so they are
//! straight (and keep their spacing) on the surface, and lie where the file puts them.
//!
//! The warp is sampled on a grid over the group's bounds (padded) with
//! [`GRID_STEP_UV`]: affine within each triangle, it is bilinear between grid points.

use glam::{DMat3, DVec3, Vec2, Vec3};

use crate::head::mesh::Mesh;

/// The warp grid's step, UV units (about 0.2 mm on the default head).
pub const GRID_STEP_UV: f32 = 1.0 / 2048.0;

/// How much the group's UV bounds are widened on each side, as a share of their size: a
/// line straight on the surface leaves the bounds of the line straight in UV by the
/// layout's bend, a few per cent.
const PAD: f32 = 0.25;

/// The most grid points along a side: a group wider than this many steps (a quarter of
/// the UV square) is evaluated in UV ([`SurfaceWarp::new`] gives `None`).
const MAX_SIDE: usize = 512;

/// The fewest grid points on the surface for a fit.
const MIN_POINTS: usize = 16;

/// A wrinkle group's warp: the UV point each grid point would have were the layout
/// affine over the group. See the module docs.
#[derive(Clone, Debug)]
pub struct SurfaceWarp {
    /// The grid's first point (u, v); the points are `GRID_STEP_UV` apart.
    origin: [f32; 2],
    cols: usize,
    rows: usize,
    /// Per grid point, row by row from `origin` (v rising): the warped UV point, NaN
    /// where no skin triangle covers it.
    points: Vec<[f32; 2]>,
}

/// Equal when made alike: the same grid and the same points, bit for bit (a point off
/// the skin is NaN, and equal to itself here, so a kept warp matches the one it was).
impl PartialEq for SurfaceWarp {
    fn eq(&self, other: &Self) -> bool {
        let bits = |p: &[f32; 2]| p.map(f32::to_bits);
        self.origin.map(f32::to_bits) == other.origin.map(f32::to_bits)
            && (self.cols, self.rows) == (other.cols, other.rows)
            && self
                .points
                .iter()
                .map(bits)
                .eq(other.points.iter().map(bits))
    }
}

/// Bit for bit, so reflexive: an `Arc<SurfaceWarp>` then compares equal to itself without
/// reading its points (the fibres, each with its warp, are compared at every bake; the
/// points' comparison was an eighth of an age step's preview bake).
impl Eq for SurfaceWarp {}

impl SurfaceWarp {
    /// The warp of a wrinkle group whose capsules lie within `bounds` (`[u0, v0, u1, v1]`,
    /// `Fibre::capsule_bounds_uv`) over `mesh`'s skin triangles in its UV layout. `None` (the
    /// group is then evaluated in UV) when the group is wider than [`MAX_SIDE`] grid
    /// steps, when fewer than [`MIN_POINTS`] grid points lie on the skin, or when the
    /// surface there is degenerate (no fit).
    pub fn new(bounds: [f32; 4], mesh: &Mesh) -> Option<Self> {
        let [u0, v0, u1, v1] = bounds;
        let (pad_u, pad_v) = (PAD * (u1 - u0), PAD * (v1 - v0));
        let origin = [u0 - pad_u, v0 - pad_v];
        let cols = ((u1 + pad_u - origin[0]) / GRID_STEP_UV).ceil() as usize + 1;
        let rows = ((v1 + pad_v - origin[1]) / GRID_STEP_UV).ceil() as usize + 1;
        if cols > MAX_SIDE || rows > MAX_SIDE {
            return None;
        }
        let (positions, uvs) = (mesh.positions(), mesh.uvs());
        let mut surface = vec![Vec3::NAN; cols * rows];
        let mut normal = Vec3::ZERO;
        let grid = |uv: Vec2| ((uv - Vec2::from(origin)) / GRID_STEP_UV).to_array();
        for tri in mesh.skin_indices().chunks_exact(3) {
            let v = [0, 1, 2].map(|k| tri[k] as usize);
            let (Some(&a), Some(&b), Some(&c)) = (uvs.get(v[0]), uvs.get(v[1]), uvs.get(v[2]))
            else {
                continue;
            };
            let p = v.map(|i| positions.get(i).copied().unwrap_or(Vec3::NAN));
            let [ga, gb, gc] = [a, b, c].map(grid);
            let lo = [0, 1].map(|k| ga[k].min(gb[k]).min(gc[k]).ceil().max(0.0));
            let hi = [0, 1].map(|k| ga[k].max(gb[k]).max(gc[k]).floor());
            if hi[0] < 0.0 || hi[1] < 0.0 || lo[0] >= cols as f32 || lo[1] >= rows as f32 {
                continue;
            }
            // A triangle across the layout's seam spans half the square or more: not a
            // piece of the surface here.
            let span = [a, b, c].map(|p| p.x);
            if span.iter().cloned().fold(f32::MIN, f32::max)
                - span.iter().cloned().fold(f32::MAX, f32::min)
                >= 0.5
            {
                continue;
            }
            let area = (b - a).perp_dot(c - a);
            if area == 0.0 || !area.is_finite() {
                continue;
            }
            normal += (p[1] - p[0]).cross(p[2] - p[0]);
            let hi = [hi[0].min(cols as f32 - 1.0), hi[1].min(rows as f32 - 1.0)];
            for y in lo[1] as usize..=hi[1] as usize {
                for x in lo[0] as usize..=hi[0] as usize {
                    let q = Vec2::new(
                        origin[0] + x as f32 * GRID_STEP_UV,
                        origin[1] + y as f32 * GRID_STEP_UV,
                    );
                    let wb = (q - a).perp_dot(c - a) / area;
                    let wc = (b - a).perp_dot(q - a) / area;
                    let wa = 1.0 - wb - wc;
                    const EDGE: f32 = -1e-5;
                    if wa >= EDGE && wb >= EDGE && wc >= EDGE {
                        surface[y * cols + x] = p[0] * wa + p[1] * wb + p[2] * wc;
                    }
                }
            }
        }
        let on: Vec<usize> = (0..surface.len())
            .filter(|&i| surface[i].is_finite())
            .collect();
        let normal = normal.try_normalize()?;
        if on.len() < MIN_POINTS {
            return None;
        }
        let centre = on.iter().map(|&i| surface[i].as_dvec3()).sum::<DVec3>() / on.len() as f64;
        let (e1, e2) = normal.any_orthonormal_pair();
        let (e1, e2) = (e1.as_dvec3(), e2.as_dvec3());
        let plane = |p: Vec3| {
            let d = p.as_dvec3() - centre;
            DVec3::new(1.0, d.dot(e1), d.dot(e2))
        };
        // Least squares: u ≈ cu·(1, x, y), v ≈ cv·(1, x, y) over the grid points.
        let (mut ata, mut atu, mut atv) = (DMat3::ZERO, DVec3::ZERO, DVec3::ZERO);
        for &i in &on {
            let r = plane(surface[i]);
            ata += DMat3::from_cols(r * r.x, r * r.y, r * r.z);
            let uv = DVec3::new(
                f64::from(origin[0]) + (i % cols) as f64 * f64::from(GRID_STEP_UV),
                f64::from(origin[1]) + (i / cols) as f64 * f64::from(GRID_STEP_UV),
                0.0,
            );
            atu += r * uv.x;
            atv += r * uv.y;
        }
        if ata.determinant().abs() < 1e-30 {
            return None;
        }
        let inv = ata.inverse();
        let (cu, cv) = (inv * atu, inv * atv);
        if !(cu.is_finite() && cv.is_finite()) {
            return None;
        }
        let points = surface
            .iter()
            .map(|&p| {
                if p.is_finite() {
                    let r = plane(p);
                    [r.dot(cu) as f32, r.dot(cv) as f32]
                } else {
                    [f32::NAN; 2]
                }
            })
            .collect();
        Some(Self {
            origin,
            cols,
            rows,
            points,
        })
    }

    /// The UV rectangle `[u0, v0, u1, v1]` the grid covers: outside it the group is 0.
    pub fn bounds_uv(&self) -> [f32; 4] {
        [
            self.origin[0],
            self.origin[1],
            self.origin[0] + (self.cols - 1) as f32 * GRID_STEP_UV,
            self.origin[1] + (self.rows - 1) as f32 * GRID_STEP_UV,
        ]
    }

    /// The warped point of UV point (`u`, `v`), bilinear between the grid's points;
    /// `None` off the grid or where a neighbouring grid point is off the skin.
    pub fn at(&self, u: f32, v: f32) -> Option<[f32; 2]> {
        let gx = (u - self.origin[0]) / GRID_STEP_UV;
        let gy = (v - self.origin[1]) / GRID_STEP_UV;
        if !(gx >= 0.0 && gy >= 0.0) {
            return None;
        }
        let (x0, y0) = (gx.floor() as usize, gy.floor() as usize);
        if x0 + 1 >= self.cols || y0 + 1 >= self.rows {
            return None;
        }
        let (tx, ty) = (gx - x0 as f32, gy - y0 as f32);
        let p = |x: usize, y: usize| self.points[y * self.cols + x];
        let [a, b, c, d] = [p(x0, y0), p(x0 + 1, y0), p(x0, y0 + 1), p(x0 + 1, y0 + 1)];
        let mix = |k: usize| {
            let low = a[k] + (b[k] - a[k]) * tx;
            let high = c[k] + (d[k] - c[k]) * tx;
            low + (high - low) * ty
        };
        let out = [mix(0), mix(1)];
        out.iter().all(|x| x.is_finite()).then_some(out)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::head::mesh::RawMesh;
    use crate::layers::wrinkles::muscle::{Fibre, Profile, Space};

    /// Rows of the test square: 5 mm apart, each shifted in u by [`SHIFT`] alternately.
    const ROWS: usize = 8;
    const SHIFT: f32 = 0.002;

    fn shift(row: usize) -> f32 {
        if row % 2 == 1 { SHIFT } else { 0.0 }
    }

    /// A flat 40 × 40 mm square (metres, z = 0) of 8 × 8 cells whose layout is
    /// u = 0.3 + x/0.2 + δ(y), v = 0.3 + y/0.2, δ alternating between 0 and 0.002 from row
    /// to row (linear between): a line straight in UV zig-zags on the surface by 0.4 mm.
    fn zig_zag_square() -> Mesh {
        let (mut positions, mut uvs, mut indices) = (Vec::new(), Vec::new(), Vec::new());
        for j in 0..=ROWS {
            for i in 0..=ROWS {
                let (x, y) = (i as f32 * 0.005, j as f32 * 0.005);
                positions.push(Vec3::new(x, y, 0.0));
                uvs.push(Vec2::new(0.3 + x / 0.2 + shift(j), 0.3 + y / 0.2));
            }
        }
        let r = (ROWS + 1) as u32;
        for j in 0..ROWS as u32 {
            for i in 0..ROWS as u32 {
                let k = j * r + i;
                indices.extend([k, k + 1, k + r + 1, k, k + r + 1, k + r]);
            }
        }
        let raw = RawMesh {
            positions,
            uvs: Some(uvs),
            indices,
            ..RawMesh::default()
        };
        Mesh::build(raw, "zig-zag square").unwrap()
    }

    /// The surface x (m) of UV point (u, v) on [`zig_zag_square`].
    fn surface_x(u: f32, v: f32) -> f32 {
        let y = (v - 0.3) * 0.2;
        let row = ((y / 0.005).floor() as usize).min(ROWS - 1);
        let t = y / 0.005 - row as f32;
        let delta = shift(row) + (shift(row + 1) - shift(row)) * t;
        (u - 0.3 - delta) * 0.2
    }

    /// A crease along v through the square's middle (u = 0.4): one wrinkle across a fibre
    /// along u.
    fn crease(space: Space) -> Fibre {
        Fibre::new([0.385, 0.4], [0.415, 0.4], 1)
            .unwrap()
            .with_rel_width(1.5)
            .unwrap()
            .with_omega_low(1.0)
            .unwrap()
            .with_profile(Profile::Crease)
            .with_space(space)
    }

    /// The deepest point of `f` along u near the square's middle, on UV row `v`.
    fn bottom(f: &Fibre, v: f32) -> f32 {
        (0..4000)
            .map(|i| 0.39 + i as f32 * 0.000_005)
            .max_by(|&a, &b| f.height_at(a, v).total_cmp(&f.height_at(b, v)))
            .unwrap()
    }

    /// The surface x of the crease's bottom along 30 UV rows across the square's middle,
    /// less their mean, at most, m.
    fn bottom_wander(f: &Fibre) -> f32 {
        let xs: Vec<f32> = (0..30)
            .map(|j| {
                let v = 0.36 + j as f32 * 0.08 / 29.0;
                surface_x(bottom(f, v), v)
            })
            .collect();
        let mean = xs.iter().sum::<f32>() / xs.len() as f32;
        xs.iter().map(|x| (x - mean).abs()).fold(0.0, f32::max)
    }

    #[test]
    fn a_line_laid_on_the_surface_is_straight_where_the_layout_bends() {
        let mesh = zig_zag_square();
        let warp =
            SurfaceWarp::new(crease(Space::Surface).capsule_bounds_uv(), &mesh).expect("a warp");
        let laid = crease(Space::Surface).with_warp(Some(std::sync::Arc::new(warp)));
        // Straight in UV, the crease zig-zags on the surface by the layout's 0.4 mm.
        let in_uv = bottom_wander(&crease(Space::Uv));
        assert!(in_uv > 0.00015, "{in_uv} m");
        // Laid on the surface, it is straight.
        let laid_wander = bottom_wander(&laid);
        assert!(laid_wander < 0.00003, "{laid_wander} m");
        // And where the file puts it, but for the layout's mean shift (0.001).
        let u = bottom(&laid, 0.4);
        assert!((u - 0.4).abs() < 0.0015, "{u}");
    }

    #[test]
    fn off_the_skin_the_group_is_zero_and_a_group_off_the_mesh_has_no_warp() {
        let mesh = zig_zag_square();
        let warp = SurfaceWarp::new(crease(Space::Surface).capsule_bounds_uv(), &mesh).unwrap();
        // The grid covers the padded bounds; beyond them, nothing.
        let [u0, v0, u1, v1] = warp.bounds_uv();
        assert!(warp.at(u0 - 0.001, 0.4).is_none() && warp.at(0.4, v1 + 0.001).is_none());
        assert!(warp.at(0.4, 0.4).is_some() && u1 > 0.46 && v0 < 0.355);
        let laid = crease(Space::Surface).with_warp(Some(std::sync::Arc::new(warp)));
        assert_eq!(laid.height_at(u0 - 0.001, 0.4), 0.0);
        // A group in an empty part of the layout.
        let far = Fibre::new([0.05, 0.05], [0.07, 0.05], 1).unwrap();
        assert!(SurfaceWarp::new(far.capsule_bounds_uv(), &mesh).is_none());
        // A group wider than the grid allows.
        let wide = Fibre::new([0.1, 0.5], [0.9, 0.5], 1).unwrap();
        assert!(SurfaceWarp::new(wide.capsule_bounds_uv(), &mesh).is_none());
        // A coarse mesh: two triangles far larger than the group still carry it.
        let coarse = Mesh::build(
            RawMesh {
                positions: vec![
                    Vec3::ZERO,
                    Vec3::new(0.2, 0.0, 0.0),
                    Vec3::new(0.2, 0.2, 0.0),
                    Vec3::new(0.0, 0.2, 0.0),
                ],
                uvs: Some(vec![
                    Vec2::new(0.25, 0.25),
                    Vec2::new(0.65, 0.25),
                    Vec2::new(0.65, 0.65),
                    Vec2::new(0.25, 0.65),
                ]),
                indices: vec![0, 1, 2, 0, 2, 3],
                ..RawMesh::default()
            },
            "coarse square",
        )
        .unwrap();
        let w =
            SurfaceWarp::new(crease(Space::Surface).capsule_bounds_uv(), &coarse).expect("a warp");
        // Affine there already: the warp is the identity.
        let p = w.at(0.4, 0.41).unwrap();
        assert!(
            (p[0] - 0.4).abs() < 1e-4 && (p[1] - 0.41).abs() < 1e-4,
            "{p:?}"
        );
    }
}
