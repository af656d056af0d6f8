//! Wavefront OBJ through `tobj`: polygons triangulated, one index per corner
//! (`single_index`, so a position with two UVs becomes two vertices), every object, group
//! and material (`usemtl`) merged into one mesh with one [`MeshPart`] each: a head exported
//! as one object keeps its eyes, lashes and teeth apart by their materials. The `.mtl`
//! files are not read (a missing one is not an error): only the materials' names count.
//! OBJ has no unit: the data is kept as written.

use std::path::Path;

use glam::{Vec2, Vec3};

use super::{MeshPart, RawMesh};
use crate::base::error::Error;

/// Reads `path` into a [`RawMesh`]; normals and UVs are `None` when no object has them
/// and NaN-marked for the vertices of objects without them.
pub fn load(path: &Path) -> Result<RawMesh, Error> {
    // Read the bytes ourselves so that a missing file is an I/O error with its path.
    let bytes = crate::base::limits::read_file(path, crate::base::limits::MAX_MESH_FILE_BYTES)?;
    load_bytes(&bytes, path)
}

/// Reads an OBJ file already in memory; `path` names it in errors.
pub fn load_bytes(bytes: &[u8], path: &Path) -> Result<RawMesh, Error> {
    let options = tobj::LoadOptions {
        triangulate: true,
        single_index: true,
        ignore_points: true,
        ignore_lines: true,
    };
    // tobj splits an object at `usemtl` only for materials its `.mtl` loader knows: every
    // material named in the file is declared by a library of our own, read first.
    let names = material_names(bytes);
    let library = |_: &Path| -> tobj::MTLLoadResult {
        let materials = names
            .iter()
            .map(|n| tobj::Material {
                name: n.clone(),
                ..Default::default()
            })
            .collect();
        let declared = names.iter().enumerate().map(|(i, n)| (n.clone(), i));
        Ok((materials, declared.collect()))
    };
    let header: &[u8] = if names.is_empty() {
        b""
    } else {
        b"mtllib agesim-material-names\n"
    };
    // The file's own `mtllib` lines declare the same names again (tobj appends them:
    // material i is also n + i, 2n + i, …): the library is ours.
    let mut reader = std::io::BufReader::new(std::io::Read::chain(header, bytes));
    let (models, _) =
        tobj::load_obj_buf(&mut reader, &options, library).map_err(|e| Error::MeshFile {
            path: path.to_owned(),
            message: format!("not a valid OBJ file: {e}"),
        })?;
    Ok(merge(&models, &names))
}

/// The names of the materials `usemtl` lines use, in order of first use.
fn material_names(bytes: &[u8]) -> Vec<String> {
    let mut names: Vec<String> = Vec::new();
    for line in bytes.split(|&b| b == b'\n') {
        let line = line.trim_ascii();
        let Some(rest) = line.strip_prefix(b"usemtl") else {
            continue;
        };
        if !rest.first().is_some_and(u8::is_ascii_whitespace) {
            continue;
        }
        let name = String::from_utf8_lossy(rest).trim().to_owned();
        if !name.is_empty() && !names.contains(&name) {
            names.push(name);
        }
    }
    names
}

fn merge(models: &[tobj::Model], materials: &[String]) -> RawMesh {
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
        let material = mesh
            .material_id
            .and_then(|i| materials.get(i % materials.len().max(1)));
        raw.parts.push(MeshPart {
            name: match material {
                Some(m) => format!("object \"{}\" material \"{m}\"", model.name),
                None => format!("object \"{}\"", model.name),
            },
            first_triangle,
            triangle_count: (mesh.indices.len() / 3) as u32,
        });
    }
    raw
}

/// `mesh` as OBJ text: its positions (each through `place`, e.g. to change units or
/// axes), its UVs and its triangles, one object. Normals and tangents are left for the
/// reader to make. For heads of other units and axes in tests and tools.
pub fn to_obj(mesh: &super::Mesh, place: impl Fn(Vec3) -> Vec3) -> String {
    use std::fmt::Write as _;
    let mut s = String::new();
    for p in mesh.positions() {
        let q = place(*p);
        let _ = writeln!(s, "v {} {} {}", q.x, q.y, q.z);
    }
    for uv in mesh.file_uvs().iter() {
        let _ = writeln!(s, "vt {} {}", uv.x, uv.y);
    }
    for [a, b, c] in mesh.triangles() {
        let (a, b, c) = (a + 1, b + 1, c + 1);
        let _ = writeln!(s, "f {a}/{a} {b}/{b} {c}/{c}");
    }
    s
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::head::mesh::test_util::{assert_close, assert_vec_close};
    use crate::head::mesh::{Mesh, MeshWarning};

    fn write(dir: &Path, name: &str, text: &str) -> std::path::PathBuf {
        let path = dir.join(name);
        std::fs::write(&path, text).unwrap();
        path
    }

    /// Two objects: a quad with UVs and normals, and a quad (a polygon, triangulated)
    /// with neither, sharing the position list.
    const TWO_OBJECTS: &str = "\
# two objects
v 0 0 0
v 1 0 0
v 1 1 0
v 0 1 0
v 2 0 0
v 3 0 0
v 3 1 0
v 2 1 0
vt 0 0
vt 1 0
vt 1 1
vt 0 1
vn 0 0 1
o A
f 1/1/1 2/2/1 3/3/1 4/4/1
o B
f 5 6 7 8
";

    /// A head exported as one object (as light-stage heads are): skin, eyes, lashes, the
    /// eye's wet layer and teeth told apart only by `usemtl`, with an `.mtl` that is not
    /// there; the skin's material used twice.
    const ONE_OBJECT_FIVE_MATERIALS: &str = "\
mtllib head.mtl
v 0 0 0
v 1 0 0
v 1 1 0
v 0 1 0
vt 0 0
vt 1 0
vt 1 1
vt 0 1
o Head
usemtl Skin
f 1/1 2/2 3/3
usemtl EyeBlend_L
f 1/1 3/3 4/4
usemtl lashes
f 1/1 2/2 4/4
usemtl lacrimal fluid
f 2/2 3/3 4/4
usemtl Teeth
f 1/1 2/2 3/3
usemtl Skin
f 1/1 3/3 4/4
";

    #[test]
    fn materials_of_one_object_are_parts_and_eyes_lashes_and_teeth_are_not_skin() {
        let dir = tempfile::tempdir().unwrap();
        let m = Mesh::load(&write(dir.path(), "head.obj", ONE_OBJECT_FIVE_MATERIALS)).unwrap();
        let parts: Vec<(&str, bool)> = m
            .parts()
            .iter()
            .map(|p| (p.name.as_str(), p.is_skin()))
            .collect();
        assert_eq!(
            parts,
            [
                ("object \"Head\" material \"Skin\"", true),
                ("object \"Head\" material \"EyeBlend_L\"", false),
                ("object \"Head\" material \"lashes\"", false),
                ("object \"Head\" material \"lacrimal fluid\"", false),
                ("object \"Head\" material \"Teeth\"", false),
                ("object \"Head\" material \"Skin\"", true),
            ]
        );
        // Only the skin's two triangles are skin.
        assert_eq!(m.skin_indices().len(), 2 * 3);
        // Without materials, one object is one part, as before.
        assert_eq!(
            material_names(b"o A\nf 1 2 3\nusemtlx y\n"),
            Vec::<String>::new()
        );
    }

    #[test]
    fn objects_merge_and_a_part_without_normals_and_uvs_is_completed() {
        let dir = tempfile::tempdir().unwrap();
        let m = Mesh::load(&write(dir.path(), "two.obj", TWO_OBJECTS)).unwrap();
        assert_eq!(m.triangle_count(), 4);
        let names: Vec<&str> = m.parts().iter().map(|p| p.name.as_str()).collect();
        assert_eq!(names, ["object \"A\"", "object \"B\""]);
        assert_vec_close(m.bounds().size(), Vec3::new(3.0, 1.0, 0.0), 0.0, "size");
        for n in m.normals() {
            assert_vec_close(*n, Vec3::Z, 1e-6, "normal");
        }
        // B had no UVs: the whole layout was regenerated, and said so.
        assert!(m.report().uvs_generated);
        assert!(
            m.report()
                .warnings
                .contains(&MeshWarning::PartialUvsReplaced {
                    parts_without_uvs: 1
                })
        );
    }

    #[test]
    fn obj_uvs_are_kept_as_written_v_up() {
        let dir = tempfile::tempdir().unwrap();
        let text = TWO_OBJECTS.split("o B").next().unwrap();
        let m = Mesh::load(&write(dir.path(), "a.obj", text)).unwrap();
        for (p, uv) in m.positions().iter().zip(m.uvs()) {
            assert_close(uv.x, p.x, 0.0, "u");
            assert_close(uv.y, p.y, 0.0, "v (OBJ is v up already)");
        }
        assert!(!m.report().normals_generated);
    }

    #[test]
    fn mirrored_uvs_give_orthonormal_tangents_with_flipped_handedness() {
        // A strip of two quads whose right half mirrors the left's UVs.
        let text = "\
v 0 0 0
v 1 0 0
v 2 0 0
v 0 1 0
v 1 1 0
v 2 1 0
vt 0 0
vt 1 0
vt 0 1
vt 1 1
f 1/1 2/2 5/4 4/3
f 2/2 3/1 6/3 5/4
";
        let dir = tempfile::tempdir().unwrap();
        let m = Mesh::load(&write(dir.path(), "mirror.obj", text)).unwrap();
        for (t, n) in m.tangents().iter().zip(m.normals()) {
            assert_close(t.truncate().dot(*n), 0.0, 1e-6, "t ⟂ n");
            assert_close(t.truncate().length(), 1.0, 1e-6, "|t|");
            // Bitangent (w · n × t) points along +v = +y on both halves.
            let b = t.w * n.cross(t.truncate());
            assert_vec_close(b, Vec3::Y, 1e-5, "bitangent");
        }
        // Per triangle: the left half has u along +x (w = +1), the right along −x (w = −1).
        for tri in m.triangles() {
            let cx: f32 = tri
                .iter()
                .map(|&i| m.positions()[i as usize].x)
                .sum::<f32>()
                / 3.0;
            for &i in &tri {
                let t = m.tangents()[i as usize];
                let (dir, w) = if cx < 1.0 {
                    (Vec3::X, 1.0)
                } else {
                    (Vec3::NEG_X, -1.0)
                };
                assert_vec_close(t.truncate(), dir, 1e-5, "tangent");
                assert_close(t.w, w, 0.0, "handedness");
            }
        }
    }

    #[test]
    fn bad_input_is_an_error_or_a_counted_warning() {
        let dir = tempfile::tempdir().unwrap();
        // Missing file.
        let err = Mesh::load(&dir.path().join("none.obj"))
            .unwrap_err()
            .to_string();
        assert!(err.contains("none.obj"), "{err}");
        // Unsupported extension.
        let err = Mesh::load(&write(dir.path(), "a.stl", "solid"))
            .unwrap_err()
            .to_string();
        assert!(err.contains("unsupported mesh format"), "{err}");
        // Out-of-range face index: tobj refuses the file.
        let err = Mesh::load(&write(
            dir.path(),
            "oob.obj",
            "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 9\n",
        ))
        .unwrap_err()
        .to_string();
        assert!(err.contains("oob.obj"), "{err}");
        // Zero triangles.
        let err = Mesh::load(&write(dir.path(), "empty.obj", "v 0 0 0\n"))
            .unwrap_err()
            .to_string();
        assert!(err.contains("empty"), "{err}");
        // NaN and infinite positions: those triangles go, the rest stays.
        let text =
            "v 0 0 0\nv 1 0 0\nv 0 1 0\nv nan 0 0\nv inf 1 1\nf 1 2 3\nf 1 2 4\nf 1 5 3\nf 1 1 2\n";
        let m = Mesh::load(&write(dir.path(), "nan.obj", text)).unwrap();
        assert_eq!(m.triangle_count(), 1);
        let w = &m.report().warnings;
        assert!(w.contains(&MeshWarning::NonFiniteTriangles(2)), "{w:?}");
        assert!(w.contains(&MeshWarning::DegenerateTriangles(1)), "{w:?}");
    }
}
