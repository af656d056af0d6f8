//! Between the head and its UV map: a click on the 3D view finds the surface point and its
//! UV (a ray against every triangle, Möller–Trumbore), and a UV on the map finds the
//! surface point it belongs to (a point-in-triangle test in UV space). Brute force over the
//! triangles: a click or a hover is one query (≈ 2 ms for the default head's triangles).

use agesim_core::Mesh;
use glam::{Mat4, Vec2, Vec3};

/// A surface point: position (mesh units) and UV.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct SurfacePoint {
    pub position: Vec3,
    pub uv: Vec2,
}

/// The nearest hit of the ray `origin + s·dir` (s > 0) with the mesh.
pub fn ray_pick(mesh: &Mesh, origin: Vec3, dir: Vec3) -> Option<SurfacePoint> {
    let (p, uv) = (mesh.positions(), mesh.uvs());
    let mut best: Option<(f32, SurfacePoint)> = None;
    for [a, b, c] in mesh.triangles() {
        let (a, b, c) = (a as usize, b as usize, c as usize);
        let (e1, e2) = (p[b] - p[a], p[c] - p[a]);
        let h = dir.cross(e2);
        let det = e1.dot(h);
        if det.abs() < 1e-12 {
            continue;
        }
        let inv = 1.0 / det;
        let s = origin - p[a];
        let u = inv * s.dot(h);
        if !(0.0..=1.0).contains(&u) {
            continue;
        }
        let q = s.cross(e1);
        let v = inv * dir.dot(q);
        if v < 0.0 || u + v > 1.0 {
            continue;
        }
        let t = inv * e2.dot(q);
        if t <= 0.0 || best.as_ref().is_some_and(|(bt, _)| *bt <= t) {
            continue;
        }
        let w = 1.0 - u - v;
        best = Some((
            t,
            SurfacePoint {
                position: origin + dir * t,
                uv: uv[a] * w + uv[b] * u + uv[c] * v,
            },
        ));
    }
    best.map(|(_, hit)| hit)
}

/// The surface point whose UV is `target` (the first triangle that contains it in UV
/// space; `None` outside the layout).
pub fn uv_to_surface(mesh: &Mesh, target: Vec2) -> Option<SurfacePoint> {
    let (p, uv) = (mesh.positions(), mesh.uvs());
    for [a, b, c] in mesh.triangles() {
        let (a, b, c) = (a as usize, b as usize, c as usize);
        let (v0, v1, v2) = (uv[b] - uv[a], uv[c] - uv[a], target - uv[a]);
        let den = v0.x * v1.y - v1.x * v0.y;
        if den.abs() < 1e-14 {
            continue;
        }
        let s = (v2.x * v1.y - v1.x * v2.y) / den;
        let t = (v0.x * v2.y - v2.x * v0.y) / den;
        if s >= 0.0 && t >= 0.0 && s + t <= 1.0 {
            return Some(SurfacePoint {
                position: p[a] + (p[b] - p[a]) * s + (p[c] - p[a]) * t,
                uv: target,
            });
        }
    }
    None
}

/// The world ray through a point of the view, from normalised device coordinates
/// (x, y in [−1, 1], y up).
pub fn view_ray(clip_from_world: Mat4, ndc: Vec2) -> (Vec3, Vec3) {
    let inv = clip_from_world.inverse();
    let near = inv.project_point3(ndc.extend(0.0));
    let far = inv.project_point3(ndc.extend(1.0));
    (near, (far - near).normalize_or_zero())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_ray_and_a_uv_find_the_same_point_on_the_skin_patch() {
        let patch = agesim_core::head::default::skin_patch();
        let b = patch.bounds();
        let c = b.centre();
        // From in front of the patch (it faces +z), straight at its centre.
        let hit = ray_pick(&patch, c + Vec3::Z, -Vec3::Z).unwrap();
        assert!((hit.position - c).length() < 1e-4, "{hit:?}");
        let back = uv_to_surface(&patch, hit.uv).unwrap();
        assert!((back.position - hit.position).length() < 1e-4, "{back:?}");
        assert!(
            ray_pick(&patch, c + Vec3::Z, Vec3::Z).is_none(),
            "behind the ray"
        );
        assert!(uv_to_surface(&patch, Vec2::new(2.0, 2.0)).is_none());
    }
}

#[cfg(test)]
mod head_tests {
    use super::*;

    #[test]
    fn a_ray_from_the_front_hits_the_default_head() {
        let head = agesim_core::head::default::default_head();
        let b = head.bounds();
        let c = b.centre();
        let eye = c + Vec3::new(0.2, 0.05, 0.56);
        let hit = ray_pick(&head, eye, (c - eye).normalize());
        let hit = hit.unwrap();
        // The front of the face, in the middle of the UV layout (docs/models.md §1 v up).
        assert!(hit.position.z > c.z, "{hit:?}");
        assert!((0.3..0.7).contains(&hit.uv.x), "{hit:?}");
        let back = uv_to_surface(&head, hit.uv).unwrap();
        assert!((back.position - hit.position).length() < 1e-3, "{back:?}");
    }
}
