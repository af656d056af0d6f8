//! Mesh data for the GPU: the interleaved vertex and the one-time subdivision for the
//! displacement mode (docs/models.md "Rendering").

use std::collections::HashMap;

use agesim_core::Mesh;
use glam::{Vec2, Vec3, Vec4};

/// One vertex as the skin pipeline reads it (48 bytes).
#[repr(C)]
#[derive(Clone, Copy, Debug, PartialEq, bytemuck::Pod, bytemuck::Zeroable)]
pub(crate) struct Vertex {
    pub position: [f32; 3],
    pub normal: [f32; 3],
    pub uv: [f32; 2],
    pub tangent: [f32; 4],
}

pub(crate) const VERTEX_ATTRIBUTES: [wgpu::VertexAttribute; 4] = wgpu::vertex_attr_array![
    0 => Float32x3, 1 => Float32x3, 2 => Float32x2, 3 => Float32x4
];

/// How the shape of an age moves one vertex (docs/models.md §13): its displacement (mesh
/// units), its displaced normal (zero: keep the mesh's own), how hollowed it is (0–1,
/// [`hollow_occlusion`]) and how much of the sky it lost to the shape around it (1 − the
/// occlusion ratio: 0 none, negative for sky gained). 32 bytes, a second vertex buffer
/// beside the mesh's; all zero is the mesh as it is.
#[repr(C)]
#[derive(Clone, Copy, Debug, Default, PartialEq, bytemuck::Pod, bytemuck::Zeroable)]
pub(crate) struct ShapeVertex {
    pub delta: [f32; 3],
    pub normal: [f32; 3],
    pub hollow: f32,
    pub sky_lost: f32,
}

pub(crate) const SHAPE_ATTRIBUTES: [wgpu::VertexAttribute; 4] = wgpu::vertex_attr_array![
    4 => Float32x3, 5 => Float32x3, 6 => Float32, 7 => Float32
];

/// How deep a hollow is for its darkening to be full, mm.
pub(crate) const HOLLOW_FULL_MM: f32 = 8.0;

/// How hollowed a vertex that the shape's deflating regions took `hollow_mm` in is, 0–1
/// (over [`HOLLOW_FULL_MM`]). A hollow sees less of the sky and the light (skin.wgsl darkens
/// it): a 10 mm temple hollow drawn without it read, blind, as "temples full", under the
/// frontal light it changed nothing.
pub(crate) fn hollow_occlusion(hollow_mm: f32) -> f32 {
    (hollow_mm / HOLLOW_FULL_MM).clamp(0.0, 1.0)
}

/// Geometry ready to upload: vertices and u32 triangle indices, and for a subdivided mesh
/// the two vertices each new one lies between (in order, after the original vertices), so
/// any per-vertex data can be subdivided the same way ([`subdivide_shape`]).
pub(crate) struct MeshData {
    pub vertices: Vec<Vertex>,
    pub indices: Vec<u32>,
    pub parents: Vec<(u32, u32)>,
}

/// A shape of the original vertices for the subdivided mesh: each new vertex the mean of
/// its two parents (normals renormalised; a zero normal stays zero: keep the mesh's).
pub(crate) fn subdivide_shape(base: &[ShapeVertex], parents: &[(u32, u32)]) -> Vec<ShapeVertex> {
    let mut out = base.to_vec();
    out.extend(parents.iter().map(|&(a, b)| {
        let (va, vb) = (base[a as usize], base[b as usize]);
        let delta = (Vec3::from(va.delta) + Vec3::from(vb.delta)) * 0.5;
        let (na, nb) = (Vec3::from(va.normal), Vec3::from(vb.normal));
        let normal = if na == Vec3::ZERO || nb == Vec3::ZERO {
            Vec3::ZERO
        } else {
            (na + nb).normalize_or(na)
        };
        ShapeVertex {
            delta: delta.to_array(),
            normal: normal.to_array(),
            hollow: 0.5 * (va.hollow + vb.hollow),
            sky_lost: 0.5 * (va.sky_lost + vb.sky_lost),
        }
    }));
    out
}

impl MeshData {
    pub(crate) fn from_mesh(mesh: &Mesh) -> Self {
        let vertices = mesh
            .positions()
            .iter()
            .zip(mesh.normals())
            .zip(mesh.uvs())
            .zip(mesh.tangents())
            .map(|(((p, n), uv), t)| Vertex {
                position: p.to_array(),
                normal: n.to_array(),
                uv: uv.to_array(),
                tangent: t.to_array(),
            })
            .collect();
        Self {
            vertices,
            indices: mesh.indices().to_vec(),
            parents: Vec::new(),
        }
    }
}

/// Splits every triangle into four at its edge midpoints (shared edges share the new
/// vertex, so no cracks open when displaced). Positions, UVs and tangents are interpolated
/// linearly, normals renormalised: the dense source head needs no smoothing scheme, only
/// more vertices for the height map to move. Done once per mesh upload, never per frame.
pub(crate) fn subdivide(data: &MeshData) -> MeshData {
    let mut vertices = data.vertices.clone();
    let mut indices = Vec::with_capacity(data.indices.len() * 4);
    let mut midpoints: HashMap<(u32, u32), u32> =
        HashMap::with_capacity(data.indices.len() * 3 / 2);
    let mut parents = Vec::with_capacity(data.indices.len() * 3 / 2);
    let mut midpoint = |a: u32, b: u32| -> u32 {
        *midpoints.entry((a.min(b), a.max(b))).or_insert_with(|| {
            parents.push((a, b));
            let (va, vb) = (vertices[a as usize], vertices[b as usize]);
            let mid = |x: [f32; 3], y: [f32; 3]| (Vec3::from(x) + Vec3::from(y)) * 0.5;
            let na = Vec3::from(va.normal);
            let ta = Vec4::from(va.tangent).truncate();
            let t = (ta + Vec4::from(vb.tangent).truncate()).normalize_or(ta);
            vertices.push(Vertex {
                position: mid(va.position, vb.position).to_array(),
                normal: mid(va.normal, vb.normal).normalize_or(na).to_array(),
                uv: ((Vec2::from(va.uv) + Vec2::from(vb.uv)) * 0.5).to_array(),
                tangent: t.extend(va.tangent[3]).to_array(),
            });
            (vertices.len() - 1) as u32
        })
    };
    for tri in data.indices.chunks_exact(3) {
        let [a, b, c] = [tri[0], tri[1], tri[2]];
        let ab = midpoint(a, b);
        let bc = midpoint(b, c);
        let ca = midpoint(c, a);
        indices.extend_from_slice(&[a, ab, ca, ab, b, bc, ca, bc, c, ab, bc, ca]);
    }
    MeshData {
        vertices,
        indices,
        parents,
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use agesim_core::head::mesh::SurfaceScale;

    #[test]
    fn subdivision_shares_edges() {
        // A 0.2 × 0.1 quad, UV 0..1 both ways: two triangles.
        let corners = [[0.0, 0.0], [1.0, 0.0], [1.0, 1.0], [0.0, 1.0]];
        let data = MeshData {
            vertices: corners
                .map(|[u, v]| Vertex {
                    position: [0.2 * u, 0.1 * v, 0.0],
                    normal: [0.0, 0.0, 1.0],
                    uv: [u, v],
                    tangent: [1.0, 0.0, 0.0, 1.0],
                })
                .to_vec(),
            indices: vec![0, 1, 2, 0, 2, 3],
            parents: Vec::new(),
        };
        let sub = subdivide(&data);
        // 5 edges (4 sides + the diagonal) → 5 new vertices; 2 → 8 triangles.
        assert_eq!(sub.vertices.len(), 9);
        assert_eq!(sub.indices.len(), 24);
        let p2: Vec<Vec3> = sub
            .vertices
            .iter()
            .map(|v| Vec3::from(v.position))
            .collect();
        let uv2: Vec<Vec2> = sub.vertices.iter().map(|v| Vec2::from(v.uv)).collect();
        let s = SurfaceScale::measure(&p2, &uv2, &sub.indices).expect("non-degenerate");
        assert!((s.units_per_u - 0.2).abs() < 1e-6);
        assert!((s.units_per_v - 0.1).abs() < 1e-6);
    }
}
