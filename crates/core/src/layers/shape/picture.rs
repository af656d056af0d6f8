//! The shape field as pictures for the editor: each vertex's movement, and per-vertex values
//! drawn in the head's UV layout.

use glam::Vec3;

use crate::head::mesh::Mesh;

/// How far each vertex moves at full age, mm (for showing the field: the editor's map view
/// and the head tinted by it).
pub fn movement_mm(full: &[Vec3], metres_per_unit: f32) -> Vec<f32> {
    full.iter()
        .map(|d| d.length() * metres_per_unit * 1000.0)
        .collect()
}

/// Per-vertex `values` over `mesh`'s skin triangles in its UV layout at `size`² (rows from
/// the top, docs/models.md §1), interpolated across each triangle; 0 where no skin
/// triangle lies.
pub fn uv_picture(mesh: &Mesh, values: &[f32], size: u32) -> Vec<f32> {
    let n = size as usize;
    let mut out = vec![0.0f32; n * n];
    let uvs = mesh.uvs();
    for tri in mesh.skin_indices().chunks_exact(3) {
        let v = [0, 1, 2].map(|k| tri[k] as usize);
        let uv = v.map(|i| uvs.get(i).copied().unwrap_or(glam::Vec2::NAN));
        let f = v.map(|i| values.get(i).copied().unwrap_or(0.0));
        crate::maps::raster::raster_uv(uv, size, 1.0, |x, y, w, _| {
            let i = y * n + x;
            out[i] = out[i].max(f[0] * w[0] + f[1] * w[1] + f[2] * w[2]);
        });
    }
    out
}
