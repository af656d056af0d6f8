//! The generator of the default head (`agesim gen-assets` writes it to
//! `assets/meshes/default-head.glb`, which the engine reads: `agesim_core::head`): a
//! mannequin-style human head and neck made by our own code.
//!
//! # Shape
//! The head is the zero set of a signed distance function ([`head_sdf`]): a cranium,
//! a face mass, jaw, chin, cheekbones, brow ridge, eye sockets with eyeballs, a nose,
//! lips, ears and a neck, joined by smooth unions (polynomial smooth minimum). It is
//! sampled by *profiles*: for each longitude φ, the cut of the surface with the half
//! plane through a vertical axis is traced as a 2D contour from the bottom of the neck
//! up to the crown, then resampled at equal arc length. The contour follows overhangs
//! (under the nose, under the jaw) that a ray cast from a centre would miss.
//!
//! # Units and axes
//! Metres (glTF convention), +Y up, the face looking along +Z, the subject's left on
//! +X. Chin to crown ≈ 0.23 m; the open neck ends at y = [`NECK_BOTTOM_Y_M`].
//!
//! # UV layout
//! - u goes around the head: u = 0.5 + φ/2π with φ the longitude from the front
//!   (+Z), positive toward +X. The front of the face is at u = 0.5, the seam at the back
//!   (u = 0 ≡ 1). Looking at the UV image is like looking at the face from the front
//!   (the subject's left, +X, is on the right of the image).
//! - v goes up along each profile, proportional to arc length: v = 0 is the open edge of
//!   the neck, v = 1 the crown.
//! - Regions (measured on this mesh; the tests of this module and of `head_assets`
//!   check the key ones, `assets/docs/uv-layout.png` shows them):
//!   - face rectangle: u ∈ [0.36, 0.64], v ∈ [0.25, 0.78] — at u = 0.5: under the chin
//!     v ≈ 0.20–0.26, chin front ≈ 0.30, lips ≈ 0.37–0.43, base of the nose ≈ 0.47, nose
//!     tip ≈ 0.50, eyes ≈ 0.555 (centres at u ≈ 0.446 / 0.554), brows ≈ 0.60, front
//!     hairline ≈ 0.78;
//!   - forehead: u ∈ [0.40, 0.60], v ∈ [0.61, 0.77] (the example fibres of docs/models.md §3,
//!     u 0.42–0.56, v 0.64–0.73, lie on it);
//!   - ears: around u ≈ 0.25 and 0.75, v ≈ 0.47–0.60;
//!   - scalp: v > 0.78 at the front, down to v ≈ 0.31 at the nape (u = 0 ≡ 1); exactly
//!     the white of `assets/masks/hair-outer.png`;
//!   - neck: v < 0.24 in front (u ∈ [0.35, 0.65]), up to the hairline at the back.
//!
//! # Start-up (< 100 ms)
//! Generating the head takes about 1 s in release on the 2-core dev machine (profile
//! tracing ~0.15–0.3 s, MikkTSpace tangents ~0.35–0.45 s, the rest of `Mesh::build`), so
//! [`default_head`] does not generate it: it reads `assets/meshes/default-head.glb`
//! (4.6 MB, built into the binary with `include_bytes!`, ≈ 40 ms including `Mesh::build`
//! under load; `benches/head.rs`, BENCHMARKS.md). The file is written by
//! `agesim gen-assets` from [`generate_default_head`], so the tangents are MikkTSpace's,
//! the ones normal maps are baked against. A test compares it with a fresh generation
//! (positions bit-identical on the dev machine, checked to 1 µm; UVs, normals and
//! tangents to a few ulps): change the generator, regenerate the assets. The skin patch
//! is flat with affine UVs, so its exact tangent frame is cheap and equal to
//! MikkTSpace's (tested): [`skin_patch`] is generated in ≈ 10 ms.

use std::f32::consts::PI;

use agesim_core::Error;
use agesim_core::mesh::{Mesh, MeshPart, RawMesh};
use glam::{Vec2, Vec3};
use rayon::prelude::*;

/// Columns of the default head around the vertical axis (the seam column is doubled).
pub const HEAD_COLUMNS: u32 = 320;
/// Rows of the default head from the neck edge to the crown.
pub const HEAD_ROWS: u32 = 200;
/// Height of the open edge of the neck, metres.
pub const NECK_BOTTOM_Y_M: f32 = -0.17;
/// The vertical axis the profiles turn around: x = 0, z = this (metres).
const AXIS_Z_M: f32 = -0.01;
/// Contour-tracing step along a profile, metres.
const TRACE_STEP_M: f32 = 0.0008;

/// The name of the default head's one part.
const HEAD_PART_NAME: &str = "default head (generated)";

/// Generates the default head from its definition: the profiles of [`head_raw`] at
/// [`HEAD_COLUMNS`] × [`HEAD_ROWS`] through [`Mesh::build`] (smooth normals, MikkTSpace
/// tangents). Deterministic. Slow for start-up (≈ 0.7–1 s in release on 2 cores): it is
/// what the shipped file is made from; use [`default_head`].
pub fn generate_default_head() -> Result<Mesh, Error> {
    Mesh::build(head_raw(HEAD_COLUMNS, HEAD_ROWS), "default head")
}

/// The raw (uncleaned) default head at a chosen resolution: `columns × rows` quads, the
/// top row fanned into the crown.
pub fn head_raw(columns: u32, rows: u32) -> RawMesh {
    let columns = columns.max(3);
    let rows = rows.max(2);
    let profiles: Vec<Vec<Vec3>> = (0..columns)
        .into_par_iter()
        .map(|i| {
            let phi = longitude(i as f32 / columns as f32);
            Profile::trace(phi).resample(rows)
        })
        .collect();

    let cols = columns as usize;
    let rows_us = rows as usize;
    // Vertices: (cols + 1) × rows grid (rows 0..rows−1), then one crown vertex per column.
    let grid_w = cols + 1;
    let mut positions = Vec::with_capacity(grid_w * rows_us + cols);
    let mut uvs = Vec::with_capacity(positions.capacity());
    for j in 0..rows_us {
        for (i, profile) in profiles.iter().cycle().take(cols + 1).enumerate() {
            positions.push(profile[j]);
            uvs.push(Vec2::new(i as f32 / cols as f32, j as f32 / rows as f32));
        }
    }
    // The crown: every profile ends on the axis at the same point; take the mean so the
    // copies are bit-identical.
    let crown = profiles.iter().map(|p| p[rows_us]).sum::<Vec3>() / cols as f32;
    let crown_first = positions.len() as u32;
    for i in 0..cols {
        positions.push(crown);
        uvs.push(Vec2::new((i as f32 + 0.5) / cols as f32, 1.0));
    }

    let at = |i: usize, j: usize| (j * grid_w + i) as u32;
    let mut indices = Vec::with_capacity(cols * rows_us * 6);
    for j in 0..rows_us - 1 {
        for i in 0..cols {
            let (a, b, c, d) = (at(i, j), at(i + 1, j), at(i + 1, j + 1), at(i, j + 1));
            indices.extend_from_slice(&[a, b, c, a, c, d]);
        }
    }
    for i in 0..cols {
        let j = rows_us - 1;
        indices.extend_from_slice(&[at(i, j), at(i + 1, j), crown_first + i as u32]);
    }
    let triangle_count = (indices.len() / 3) as u32;
    RawMesh {
        positions,
        uvs: Some(uvs),
        indices,
        parts: vec![MeshPart {
            name: HEAD_PART_NAME.to_owned(),
            first_triangle: 0,
            triangle_count,
        }],
        ..RawMesh::default()
    }
}

/// The point of the default head's surface at (u, v) of its UV layout (module docs),
/// for painting masks that match the layout. `u` wraps; `v` is clamped to [0,1].
/// Traces one profile per call: evaluate whole columns with [`head_column`] instead.
pub fn head_point(u: f32, v: f32) -> Vec3 {
    Profile::trace(longitude(u)).at(v)
}

/// The surface points of the default head along the column at `u`, for each `v` of
/// `vs`.
pub fn head_column(u: f32, vs: &[f32]) -> Vec<Vec3> {
    let profile = Profile::trace(longitude(u));
    vs.iter().map(|&v| profile.at(v)).collect()
}

/// Longitude φ (radians, 0 = front, positive toward +X) of the column at `u`.
fn longitude(u: f32) -> f32 {
    (u.rem_euclid(1.0) - 0.5) * 2.0 * PI
}

/// One traced profile of the base shape ([`base_sdf`]): points (ρ, y) in the half plane
/// at longitude φ, with their cumulative arc length.
struct Profile {
    phi: f32,
    points: Vec<Vec2>,
    arc_m: Vec<f32>,
}

impl Profile {
    fn to_3d(phi: f32, p: Vec2) -> Vec3 {
        Vec3::new(p.x * phi.sin(), p.y, AXIS_Z_M + p.x * phi.cos())
    }

    fn base(phi: f32, p: Vec2) -> f32 {
        base_sdf(Self::to_3d(phi, p))
    }

    /// Gradient of the base field in the half plane (central differences).
    fn base_grad(phi: f32, p: Vec2) -> Vec2 {
        let e = 1e-5;
        Vec2::new(
            Self::base(phi, p + Vec2::new(e, 0.0)) - Self::base(phi, p - Vec2::new(e, 0.0)),
            Self::base(phi, p + Vec2::new(0.0, e)) - Self::base(phi, p - Vec2::new(0.0, e)),
        ) / (2.0 * e)
    }

    /// Traces the contour f = 0 of [`base_sdf`] in the half plane at `phi`, from the
    /// neck's edge up to the axis (the crown): predictor step along the tangent, then
    /// Newton corrections back onto the surface.
    fn trace(phi: f32) -> Self {
        let f = |p: Vec2| Self::base(phi, p);
        // Start: where the neck's edge crosses the surface (the axis is inside the neck).
        let (mut lo, mut hi) = (0.0f32, 0.3f32);
        for _ in 0..40 {
            let mid = 0.5 * (lo + hi);
            if f(Vec2::new(mid, NECK_BOTTOM_Y_M)) < 0.0 {
                lo = mid;
            } else {
                hi = mid;
            }
        }
        let mut p = Vec2::new(0.5 * (lo + hi), NECK_BOTTOM_Y_M);
        let mut points = vec![p];
        let mut arc_m = vec![0.0];
        let mut g = Self::base_grad(phi, p);
        for _ in 0..5000 {
            // Tangent with the inside (toward the axis) on the left: upward on the neck.
            let t = Vec2::new(-g.y, g.x).normalize_or_zero();
            let mut q = p + TRACE_STEP_M * t;
            for _ in 0..2 {
                g = Self::base_grad(phi, q);
                q -= f(q) * g / g.length_squared().max(1e-12);
            }
            if q.x <= 0.0 {
                // Crossed the axis: end exactly on it.
                let s = p.x / (p.x - q.x);
                let end = Vec2::new(0.0, p.y + s * (q.y - p.y));
                arc_m.push(arc_m[arc_m.len() - 1] + (end - p).length());
                points.push(end);
                break;
            }
            arc_m.push(arc_m[arc_m.len() - 1] + (q - p).length());
            points.push(q);
            p = q;
        }
        Self { phi, points, arc_m }
    }

    /// The base-shape point at fraction `v` of the arc length, in the half plane.
    fn base_at(&self, v: f32) -> Vec2 {
        let total = self.arc_m[self.arc_m.len() - 1];
        let s = v.clamp(0.0, 1.0) * total;
        let k = self
            .arc_m
            .partition_point(|&a| a < s)
            .clamp(1, self.arc_m.len() - 1);
        let (a0, a1) = (self.arc_m[k - 1], self.arc_m[k]);
        let t = if a1 > a0 {
            ((s - a0) / (a1 - a0)).clamp(0.0, 1.0)
        } else {
            0.0
        };
        self.points[k - 1].lerp(self.points[k], t)
    }

    /// The detailed surface ([`head_sdf`]) point for fraction `v`: the base point moved
    /// along the base normal (in the half plane) to the nearest crossing of the detailed
    /// surface — features are displacements of the base.
    fn at(&self, v: f32) -> Vec3 {
        let b = self.base_at(v);
        // The neck's edge and the crown stay where the base put them (the ring stays
        // planar, the crown on the axis).
        if v <= 0.0 || v >= 1.0 {
            return Self::to_3d(self.phi, b);
        }
        let n = Self::base_grad(self.phi, b).normalize_or_zero();
        let f = |t: f32| head_sdf(Self::to_3d(self.phi, b + t * n));
        let mut t = 0.0f32;
        let mut d = f(t);
        let outward = d < 0.0;
        for _ in 0..64 {
            if d.abs() < 1e-6 || t.abs() > MAX_DETAIL_M {
                break;
            }
            let step = (0.9 * d.abs()).max(1e-4);
            let next = if outward { t + step } else { t - step };
            let dn = f(next);
            if (dn < 0.0) != (d < 0.0) {
                // Bracketed: bisect.
                let (mut lo, mut hi) = (t, next);
                for _ in 0..20 {
                    let mid = 0.5 * (lo + hi);
                    if (f(mid) < 0.0) == (d < 0.0) {
                        lo = mid;
                    } else {
                        hi = mid;
                    }
                }
                t = 0.5 * (lo + hi);
                break;
            }
            t = next;
            d = dn;
        }
        Self::to_3d(self.phi, b + t.clamp(-MAX_DETAIL_M, MAX_DETAIL_M) * n)
    }

    /// `rows + 1` points at equal base arc length from the neck (row 0) to the crown.
    fn resample(&self, rows: u32) -> Vec<Vec3> {
        (0..=rows)
            .map(|j| self.at(j as f32 / rows as f32))
            .collect()
    }
}

/// The largest displacement of a detail (the nose tip) off the base shape, metres.
const MAX_DETAIL_M: f32 = 0.05;

// ---- signed distance primitives (after Inigo Quilez's catalogue) -------------------

fn ellipsoid(p: Vec3, centre: Vec3, radii: Vec3) -> f32 {
    let q = p - centre;
    let k0 = (q / radii).length();
    let k1 = (q / (radii * radii)).length();
    if k1 == 0.0 {
        -radii.min_element()
    } else {
        k0 * (k0 - 1.0) / k1
    }
}

fn capsule(p: Vec3, a: Vec3, b: Vec3, radius: f32) -> f32 {
    let (pa, ba) = (p - a, b - a);
    let h = (pa.dot(ba) / ba.dot(ba)).clamp(0.0, 1.0);
    (pa - ba * h).length() - radius
}

/// A cone with rounded ends from `a` (radius `ra`) to `b` (radius `rb`).
fn round_cone(p: Vec3, a: Vec3, b: Vec3, ra: f32, rb: f32) -> f32 {
    let (pa, ba) = (p - a, b - a);
    let h = (pa.dot(ba) / ba.dot(ba)).clamp(0.0, 1.0);
    (pa - ba * h).length() - (ra + (rb - ra) * h)
}

/// Polynomial smooth minimum: union with a blend of width `k` metres.
fn smin(a: f32, b: f32, k: f32) -> f32 {
    let h = (k - (a - b).abs()).max(0.0) / k;
    a.min(b) - h * h * k * 0.25
}

/// Smooth subtraction of `b` from `a`.
fn smax(a: f32, b: f32, k: f32) -> f32 {
    -smin(-a, -b, k)
}

/// The smooth base shape the profiles are traced on: skull, face mass, jaw, chin and
/// neck (signed distance, approximately, metres).
pub fn base_sdf(p: Vec3) -> f32 {
    let m = Vec3::new(p.x.abs(), p.y, p.z);
    let v = Vec3::new;
    let mut d = ellipsoid(p, v(0.0, 0.03, -0.005), v(0.074, 0.095, 0.1));
    d = smin(
        d,
        ellipsoid(p, v(0.0, -0.02, 0.035), v(0.058, 0.066, 0.058)),
        0.03,
    );
    // Jaw: two mandible branches from the angle of the jaw to the chin.
    let jaw = capsule(m, v(0.05, -0.06, -0.012), v(0.012, -0.092, 0.07), 0.012);
    d = smin(d, jaw, 0.025);
    d = smin(
        d,
        ellipsoid(p, v(0.0, -0.09, 0.078), v(0.022, 0.017, 0.016)),
        0.015,
    );
    // Muzzle (the teeth arch under the lips): keeps the base upright where the lips sit,
    // so that they are small displacements along a horizontal normal.
    d = smin(
        d,
        ellipsoid(p, v(0.0, -0.055, 0.07), v(0.033, 0.034, 0.03)),
        0.015,
    );
    // Neck, leaning slightly forward, blended wide into the jaw and skull base.
    let neck = capsule(p, v(0.0, -0.4, -0.035), v(0.0, -0.04, -0.012), 0.052);
    smin(d, neck, 0.035)
}

/// Signed distance (approximately, metres; negative inside) to the default head: the
/// [`base_sdf`] with the features added.
pub fn head_sdf(p: Vec3) -> f32 {
    // Bilateral features use the mirrored point.
    let m = Vec3::new(p.x.abs(), p.y, p.z);
    let v = Vec3::new;
    let mut d = base_sdf(p);
    // Cheekbones.
    d = smin(
        d,
        ellipsoid(m, v(0.045, -0.005, 0.052), v(0.024, 0.017, 0.03)),
        0.02,
    );
    // Brow ridge.
    let brow = capsule(m, v(0.0, 0.027, 0.093), v(0.046, 0.03, 0.076), 0.007);
    d = smin(d, brow, 0.012);
    // Eye sockets, then eyeballs in them.
    let socket = ellipsoid(m, v(0.032, 0.008, 0.094), v(0.02, 0.012, 0.014));
    d = smax(d, -socket, 0.01);
    d = smin(
        d,
        ellipsoid(m, v(0.032, 0.007, 0.071), v(0.013, 0.0105, 0.013)),
        0.006,
    );
    // Nose: bridge to tip, wings.
    let nose = round_cone(
        p,
        v(0.0, 0.012, 0.092),
        v(0.0, -0.028, 0.117),
        0.0065,
        0.0105,
    );
    d = smin(d, nose, 0.01);
    d = smin(
        d,
        ellipsoid(m, v(0.0115, -0.029, 0.1), v(0.0065, 0.0065, 0.008)),
        0.008,
    );
    // Lips and the mouth line.
    d = smin(
        d,
        ellipsoid(p, v(0.0, -0.0495, 0.097), v(0.024, 0.0075, 0.011)),
        0.006,
    );
    d = smin(
        d,
        ellipsoid(p, v(0.0, -0.0625, 0.094), v(0.021, 0.008, 0.011)),
        0.006,
    );
    d = smax(
        d,
        -ellipsoid(p, v(0.0, -0.0558, 0.106), v(0.022, 0.0016, 0.011)),
        0.004,
    );
    // Ears: a flattened disc with a hollow.
    let ear = ellipsoid(m, v(0.074, 0.0, -0.014), v(0.011, 0.03, 0.019));
    d = smin(d, ear, 0.008);
    smax(
        d,
        -ellipsoid(m, v(0.086, -0.004, -0.01), v(0.005, 0.012, 0.008)),
        0.004,
    )
}

#[cfg(test)]
mod tests {
    #![allow(clippy::unwrap_used, clippy::expect_used)]
    use std::collections::HashMap;

    use agesim_core::mesh::TangentSource;
    use agesim_core::mesh::normals::weld_by_position;

    use super::*;

    fn head() -> &'static Mesh {
        static HEAD: std::sync::OnceLock<Mesh> = std::sync::OnceLock::new();
        HEAD.get_or_init(|| generate_default_head().unwrap())
    }

    #[test]
    fn the_head_has_a_triangle_count_in_range_and_no_repairs() {
        let m = head();
        assert!(
            (50_000..=200_000).contains(&m.triangle_count()),
            "{}",
            m.triangle_count()
        );
        assert!(m.report().warnings.is_empty(), "{:?}", m.report().warnings);
        assert!(!m.report().normals_generated || m.normals().len() == m.vertex_count());
        assert!(!m.report().uvs_generated);
    }

    #[test]
    fn the_head_is_human_sized_in_metres() {
        let b = head().bounds();
        // The chin is the lowest point of the front column above the neck.
        let vs: Vec<f32> = (0..=100).map(|j| j as f32 / 100.0).collect();
        let chin = head_column(0.5, &vs)
            .iter()
            .filter(|p| p.z > 0.06)
            .map(|p| p.y)
            .fold(f32::INFINITY, f32::min);
        let crown = b.max.y;
        // A real head is about 0.23 m from chin to crown.
        assert!(
            (0.22..0.24).contains(&(crown - chin)),
            "chin {chin}, crown {crown}"
        );
        assert_eq!(b.min.y, NECK_BOTTOM_Y_M);
        let width = b.size().x;
        assert!((0.14..0.19).contains(&width), "width with ears {width}");
    }

    #[test]
    fn the_head_is_closed_except_at_the_neck() {
        let m = head();
        let weld = weld_by_position(m.positions());
        let mut edges: HashMap<(u32, u32), u32> = HashMap::new();
        for t in m.triangles() {
            let w = t.map(|i| weld[i as usize]);
            for k in 0..3 {
                let (a, b) = (w[k], w[(k + 1) % 3]);
                *edges.entry((a.min(b), a.max(b))).or_default() += 1;
            }
        }
        let mut boundary = 0;
        for (&(a, b), &count) in &edges {
            assert!(count <= 2, "edge {a}-{b} shared by {count} triangles");
            if count == 1 {
                boundary += 1;
                for v in [a, b] {
                    let y = m.positions()[v as usize].y;
                    assert!(
                        (y - NECK_BOTTOM_Y_M).abs() < 1e-5,
                        "open edge at y = {y}, not the neck"
                    );
                }
            }
        }
        assert_eq!(boundary, HEAD_COLUMNS as usize, "one open ring at the neck");
    }

    #[test]
    fn the_head_normals_point_outward() {
        let m = head();
        // Vertex normals agree with the outward gradient of the field.
        let e = 1e-5;
        let mut disagree = 0;
        for (p, n) in m.positions().iter().zip(m.normals()) {
            let g = Vec3::new(
                head_sdf(*p + Vec3::X * e) - head_sdf(*p - Vec3::X * e),
                head_sdf(*p + Vec3::Y * e) - head_sdf(*p - Vec3::Y * e),
                head_sdf(*p + Vec3::Z * e) - head_sdf(*p - Vec3::Z * e),
            );
            if n.dot(g) <= 0.0 {
                disagree += 1;
            }
        }
        assert!(
            disagree * 500 < m.vertex_count(),
            "{disagree} normals point inward"
        );
        // And the triangles wind counter-clockwise seen from outside: the signed volume,
        // with the neck closed by a fan to its centre, is positive and plausible.
        let neck_centre = Vec3::new(0.0, NECK_BOTTOM_Y_M, 0.0);
        let volume_m3: f32 = m
            .triangles()
            .map(|t| {
                let [a, b, c] = t.map(|i| m.positions()[i as usize] - neck_centre);
                a.dot(b.cross(c)) / 6.0
            })
            .sum();
        // Head ≈ 4 litres, neck ≈ 1.5 litres.
        assert!((0.003..0.008).contains(&volume_m3), "volume {volume_m3} m³");
    }

    #[test]
    fn the_head_uvs_are_in_the_unit_square_and_follow_the_layout() {
        let m = head();
        assert!(
            m.uvs()
                .iter()
                .all(|uv| (0.0..=1.0).contains(&uv.x) && (0.0..=1.0).contains(&uv.y))
        );
        // u = 0.5 is the front (+z), u = 0.75 the subject's left (+x).
        let front = head_point(0.5, 0.6);
        assert!(front.z > 0.08 && front.x.abs() < 1e-4, "{front}");
        let left = head_point(0.75, 0.6);
        assert!(left.x > 0.06, "{left}");
        // The example fibres of docs/models.md §3 lie on the forehead: above the eyes and brows,
        // below the hairline, on the front of the head.
        for (u, v) in [
            (0.423, 0.727),
            (0.439, 0.640),
            (0.556, 0.727),
            (0.537, 0.638),
        ] {
            let p = head_point(u, v);
            assert!(p.y > 0.03 && p.y < 0.085 && p.z > 0.055, "({u}, {v}) → {p}");
        }
    }

    #[test]
    fn the_head_is_deterministic() {
        let a = head_raw(32, 24);
        let b = head_raw(32, 24);
        assert_eq!(a.positions, b.positions);
    }

    /// Angle between two directions, radians (robust near 0).
    fn angle(a: Vec3, b: Vec3) -> f32 {
        a.cross(b).length().atan2(a.dot(b))
    }

    #[test]
    fn the_shipped_head_file_matches_a_fresh_generation() {
        // Guards assets/meshes/default-head.glb against going stale: rerun
        // `cargo run -p agesim -- gen-assets --out assets` when this fails. A tolerance,
        // not bytes: `sin`/`cos` of the platform's libm may differ in the last ulp.
        let shipped =
            agesim_core::head::shipped_default_head().expect("the built-in head file reads");
        let fresh = head();
        assert_eq!(shipped.vertex_count(), fresh.vertex_count(), "vertex count");
        assert_eq!(shipped.indices(), fresh.indices(), "triangles");
        // Provenance differs by design: the shipped file reports what its loader saw.
        assert_eq!(shipped.parts().len(), fresh.parts().len());
        let mut worst = [0.0f32; 4];
        for k in 0..fresh.vertex_count() {
            let (s, f) = (shipped.tangents()[k], fresh.tangents()[k]);
            assert_eq!(s.w, f.w, "handedness of vertex {k}");
            let d = [
                (shipped.positions()[k] - fresh.positions()[k]).length(),
                (shipped.uvs()[k] - fresh.uvs()[k]).length(),
                angle(shipped.normals()[k], fresh.normals()[k]),
                angle(s.truncate(), f.truncate()),
            ];
            for (w, d) in worst.iter_mut().zip(d) {
                *w = w.max(d);
            }
        }
        let [pos_m, uv, normal_rad, tangent_rad] = worst;
        assert!(pos_m <= 1e-6, "positions differ by {pos_m} m");
        assert!(uv <= 1e-6, "UVs differ by {uv}");
        assert!(normal_rad <= 1e-5, "normals differ by {normal_rad} rad");
        assert!(tangent_rad <= 1e-5, "tangents differ by {tangent_rad} rad");
        assert_eq!(shipped.bounds().min.y, NECK_BOTTOM_Y_M);
    }

    #[test]
    fn the_default_head_is_this_generation() {
        let m = agesim_core::head::default_head();
        assert_eq!(m.report().tangent_source, Some(TangentSource::File));
        assert_eq!(m.vertex_count(), head().vertex_count());
    }
}
