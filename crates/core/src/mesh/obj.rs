//! Wavefront OBJ through `tobj`: polygons triangulated, one index per corner
//! (`single_index`, so a position with two UVs becomes two vertices), every object and
//! group merged into one mesh with one [`MeshPart`] each. Materials are ignored (a missing
//! `.mtl` is not an error). OBJ has no unit: the data is kept as written.

use std::path::Path;

use glam::{Vec2, Vec3};

use super::{MeshPart, RawMesh};
use crate::error::Error;

/// Reads `path` into a [`RawMesh`]; normals and UVs are `None` when no object has them
/// and NaN-marked for the vertices of objects without them.
pub fn load(path: &Path) -> Result<RawMesh, Error> {
    // Read the bytes ourselves so that a missing file is an I/O error with its path.
    let bytes = std::fs::read(path).map_err(|e| Error::io(path, e))?;
    let options = tobj::LoadOptions {
        triangulate: true,
        single_index: true,
        ignore_points: true,
        ignore_lines: true,
    };
    let (models, _materials) =
        tobj::load_obj_buf(&mut bytes.as_slice(), &options, |_| Ok(Default::default())).map_err(
            |e| Error::MeshFile {
                path: path.to_owned(),
                message: format!("not a valid OBJ file: {e}"),
            },
        )?;
    Ok(merge(&models))
}

fn merge(models: &[tobj::Model]) -> RawMesh {
    let any_normals = models.iter().any(|m| !m.mesh.normals.is_empty());
    let any_uvs = models.iter().any(|m| !m.mesh.texcoords.is_empty());
    let mut raw = RawMesh {
        normals: any_normals.then(Vec::new),
        uvs: any_uvs.then(Vec::new),
        ..RawMesh::default()
    };
    for model in models {
        let mesh = &model.mesh;
        let base = raw.positions.len() as u32;
        let count = mesh.positions.len() / 3;
        raw.positions.extend(
            mesh.positions
                .chunks_exact(3)
                .map(|p| Vec3::new(p[0], p[1], p[2])),
        );
        if let Some(normals) = raw.normals.as_mut() {
            if mesh.normals.len() == mesh.positions.len() {
                normals.extend(
                    mesh.normals
                        .chunks_exact(3)
                        .map(|n| Vec3::new(n[0], n[1], n[2])),
                );
            } else {
                normals.extend(std::iter::repeat_n(Vec3::NAN, count));
            }
        }
        if let Some(uvs) = raw.uvs.as_mut() {
            if mesh.texcoords.len() == count * 2 {
                uvs.extend(
                    mesh.texcoords
                        .chunks_exact(2)
                        .map(|t| Vec2::new(t[0], t[1])),
                );
            } else {
                uvs.extend(std::iter::repeat_n(Vec2::NAN, count));
            }
        }
        let first_triangle = (raw.indices.len() / 3) as u32;
        // Out-of-range indices stay out of range after the offset (saturating), so that
        // Mesh::build drops and counts them instead of pointing into another object.
        raw.indices.extend(mesh.indices.iter().map(|&i| {
            if (i as usize) < count {
                base + i
            } else {
                u32::MAX
            }
        }));
        raw.parts.push(MeshPart {
            name: format!("object \"{}\"", model.name),
            first_triangle,
            triangle_count: (mesh.indices.len() / 3) as u32,
        });
    }
    raw
}
