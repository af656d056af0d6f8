//! glTF 2.0 (`.gltf` with embedded `data:` or external buffers, `.glb`) through the
//! `gltf` crate.
//!
//! Every triangle primitive (triangles, strips and fans) of every node of the default
//! scene (the first scene when none is marked default; every mesh untransformed when the
//! file has no scene) is merged into one mesh, with the node's world transform applied to
//! positions, normals (inverse transpose) and tangents; a mirroring transform (negative
//! determinant) flips the triangle winding so faces stay outward. Texture coordinates
//! set 0 are read and v is flipped to v-up (docs/models.md §1). Points and lines are skipped and
//! counted. Images and materials are not read, so a missing texture file is no error.
//!
//! Attribute formats: POSITION, NORMAL and TANGENT must be float; TEXCOORD_0 may be
//! float or normalised unsigned byte/short (core glTF). The signed and non-normalised
//! integer forms that `KHR_mesh_quantization` allows are refused with a clear error
//! naming the mesh, primitive and attribute: the `gltf` crate's typed readers do not
//! decode them. Re-export such a file without quantization (e.g. `gltf-transform
//! dequantize`). Other required extensions (Draco, meshopt) are refused the same way.

use std::path::Path;

use ::gltf::Semantic;
use ::gltf::accessor::{DataType, Dimensions};
use ::gltf::mesh::Mode;
use glam::{Mat3, Mat4, Vec2, Vec3, Vec4};

use super::{MeshPart, MeshWarning, RawMesh};
use crate::base::error::Error;

pub use super::glb_write::{
    GlbExtraMesh, GlbMaterial, GlbMorph, glb_container, write_glb, write_glb_with_extras,
    write_glb_with_material, write_glb_with_materials, write_glb_with_morph,
};

/// Whether a buffer URI stays inside the glTF's folder: a `data:` URI, or a relative path
/// (percent-encoding decoded) with no `..` component, no scheme, no root or drive.
pub(crate) fn check_uri(uri: &str) -> Result<(), &'static str> {
    if uri.starts_with("data:") {
        return Ok(());
    }
    let decoded = decode_uri(uri);
    if decoded.contains(':') {
        return Err("names a scheme or a drive");
    }
    if decoded.starts_with('/') || decoded.starts_with('\\') {
        return Err("is an absolute path");
    }
    if decoded.split(['/', '\\']).any(|c| c == "..") {
        return Err("climbs out of the glTF's folder");
    }
    Ok(())
}

/// `%xx` escapes of a URI decoded (invalid escapes kept as they are).
pub(crate) fn decode_uri(uri: &str) -> String {
    let bytes = uri.as_bytes();
    let mut out = Vec::with_capacity(bytes.len());
    let mut i = 0;
    while i < bytes.len() {
        if bytes[i] == b'%'
            && i + 2 < bytes.len()
            && let Ok(v) = u8::from_str_radix(&uri[i + 1..i + 3], 16)
        {
            out.push(v);
            i += 3;
            continue;
        }
        out.push(bytes[i]);
        i += 1;
    }
    String::from_utf8_lossy(&out).into_owned()
}

/// Parses a glTF or GLB document. The `gltf` crate's validation indexes arrays with
/// indices the file gives (gltf-json 1.4: a primitive whose POSITION names a missing
/// accessor panics); a file must never crash agesim, so a panic in the reader is caught
/// and reported as a malformed file.
pub(crate) fn parse(bytes: &[u8]) -> Result<::gltf::Gltf, String> {
    match std::panic::catch_unwind(|| ::gltf::Gltf::from_slice(bytes)) {
        Ok(Ok(g)) => Ok(g),
        Ok(Err(e)) => Err(format!("not a valid glTF 2.0 file: {e}")),
        Err(_) => Err(
            "not a valid glTF 2.0 file: it refers to parts it does not have (the glTF reader gave up on it)"
                .into(),
        ),
    }
}

/// Reads `path` into a [`RawMesh`] (see the module docs).
pub fn load(path: &Path) -> Result<RawMesh, Error> {
    let bytes = crate::base::limits::read_file(path, crate::base::limits::MAX_MESH_FILE_BYTES)?;
    load_bytes(&bytes, path)
}

/// Reads a glTF or GLB file already in memory; `path` names it in errors and locates
/// external buffers (relative to its folder).
pub fn load_bytes(bytes: &[u8], path: &Path) -> Result<RawMesh, Error> {
    let fail = |message: String| Error::MeshFile {
        path: path.to_owned(),
        message,
    };
    let gltf = parse(bytes).map_err(fail)?;
    for ext in gltf.document.extensions_required() {
        if ext != "KHR_mesh_quantization" {
            return Err(fail(format!("requires the unsupported extension {ext}")));
        }
    }
    for buffer in gltf.document.buffers() {
        if let ::gltf::buffer::Source::Uri(uri) = buffer.source() {
            check_uri(uri).map_err(|why| {
                fail(format!(
                    "buffer {} has the URI \"{}\", which {why}: only data: URIs and files inside the glTF's own folder are read",
                    buffer.index(),
                    crate::base::limits::shorten(uri, 80)
                ))
            })?;
        }
    }
    let buffers = ::gltf::import_buffers(&gltf.document, path.parent(), gltf.blob.clone())
        .map_err(|e| fail(format!("cannot read its buffers: {e}")))?;
    let mut loader = Loader {
        buffers: &buffers,
        acc: Accumulator::default(),
    };
    match gltf
        .document
        .default_scene()
        .or_else(|| gltf.document.scenes().next())
    {
        Some(scene) => {
            for node in scene.nodes() {
                loader.node(&node, Mat4::IDENTITY, 0).map_err(fail)?;
            }
        }
        None => {
            loader.acc.warnings.push(MeshWarning::Note(
                "the file has no scene: every mesh loaded without transform".to_owned(),
            ));
            for mesh in gltf.document.meshes() {
                loader
                    .mesh(&mesh, Mat4::IDENTITY, "no node")
                    .map_err(fail)?;
            }
        }
    }
    Ok(loader.acc.finish())
}

/// Per-vertex data of all primitives so far; `None` entries are vertices of primitives
/// without that attribute.
#[derive(Default)]
struct Accumulator {
    positions: Vec<Vec3>,
    normals: Vec<Option<Vec3>>,
    uvs: Vec<Option<Vec2>>,
    tangents: Vec<Option<Vec4>>,
    indices: Vec<u32>,
    parts: Vec<MeshPart>,
    warnings: Vec<MeshWarning>,
    non_triangle: usize,
}

impl Accumulator {
    fn finish(mut self) -> RawMesh {
        if self.non_triangle > 0 {
            self.warnings
                .push(MeshWarning::NonTriangleParts(self.non_triangle));
        }
        fn column<T: Copy>(v: Vec<Option<T>>, missing: T) -> Option<Vec<T>> {
            v.iter()
                .any(Option::is_some)
                .then(|| v.into_iter().map(|x| x.unwrap_or(missing)).collect())
        }
        RawMesh {
            positions: self.positions,
            normals: column(self.normals, Vec3::NAN),
            uvs: column(self.uvs, Vec2::NAN),
            tangents: column(self.tangents, Vec4::NAN),
            indices: self.indices,
            parts: self.parts,
            warnings: self.warnings,
        }
    }
}

struct Loader<'a> {
    buffers: &'a [::gltf::buffer::Data],
    acc: Accumulator,
}

/// The name of the hair mesh an agesim export writes beside the head.
pub const AGESIM_HAIR_MESH: &str = "hair";

/// Deeper node hierarchies than this are refused (a cyclic or hostile file).
const MAX_NODE_DEPTH: usize = 256;

impl Loader<'_> {
    fn node(&mut self, node: &::gltf::Node, parent: Mat4, depth: usize) -> Result<(), String> {
        if depth > MAX_NODE_DEPTH {
            return Err(format!("node hierarchy deeper than {MAX_NODE_DEPTH}"));
        }
        let world = parent * Mat4::from_cols_array_2d(&node.transform().matrix());
        if let Some(mesh) = node.mesh() {
            let name = node
                .name()
                .map_or_else(|| format!("#{}", node.index()), |n| format!("\"{n}\""));
            self.mesh(&mesh, world, &format!("node {name}"))?;
        }
        for child in node.children() {
            self.node(&child, world, depth + 1)?;
        }
        Ok(())
    }

    fn mesh(&mut self, mesh: &::gltf::Mesh, world: Mat4, node: &str) -> Result<(), String> {
        // The hair an agesim export carries (ribbons without UVs, made again from the
        // head): read as skin, it would leave the head's UVs partial (regenerated whole).
        let agesim_hair = mesh.name() == Some(AGESIM_HAIR_MESH)
            && mesh.primitives().all(|p| {
                p.get(&Semantic::TexCoords(0)).is_none()
                    && p.material()
                        .name()
                        .is_some_and(|n| n.starts_with("agesim hair"))
            });
        if agesim_hair {
            self.acc.warnings.push(MeshWarning::Note(
                "the hair of an agesim export is left out: agesim grows the head's hair itself"
                    .into(),
            ));
            return Ok(());
        }
        let mesh_name = mesh
            .name()
            .map_or_else(|| format!("#{}", mesh.index()), |n| format!("\"{n}\""));
        for prim in mesh.primitives() {
            let what = format!("mesh {mesh_name} primitive {} ({node})", prim.index());
            self.primitive(&prim, world, what)?;
        }
        Ok(())
    }

    fn primitive(
        &mut self,
        prim: &::gltf::Primitive,
        world: Mat4,
        what: String,
    ) -> Result<(), String> {
        if !matches!(
            prim.mode(),
            Mode::Triangles | Mode::TriangleStrip | Mode::TriangleFan
        ) {
            self.acc.non_triangle += 1;
            return Ok(());
        }
        let check = |semantic: Semantic, allowed: &[(DataType, Dimensions, Option<bool>)]| {
            let Some(acc) = prim.get(&semantic) else {
                return Ok(None);
            };
            let ok = allowed.iter().any(|&(ty, dim, normalized)| {
                acc.data_type() == ty
                    && acc.dimensions() == dim
                    && normalized.is_none_or(|n| n == acc.normalized())
            });
            if !ok {
                let quantized = !matches!(acc.data_type(), DataType::F32);
                return Err(format!(
                    "{what}: attribute {semantic:?} is {:?} {:?}{}; supported: {}{}",
                    acc.dimensions(),
                    acc.data_type(),
                    if acc.normalized() { " normalized" } else { "" },
                    allowed
                        .iter()
                        .map(|(t, d, n)| format!(
                            "{d:?} {t:?}{}",
                            if *n == Some(true) { " normalized" } else { "" }
                        ))
                        .collect::<Vec<_>>()
                        .join(" or "),
                    if quantized {
                        " (quantized attributes of KHR_mesh_quantization are not supported)"
                    } else {
                        ""
                    }
                ));
            }
            Ok(Some(acc.count()))
        };
        let Some(count) = check(
            Semantic::Positions,
            &[(DataType::F32, Dimensions::Vec3, None)],
        )?
        else {
            return Err(format!("{what}: has no POSITION attribute"));
        };
        let normal_count = check(
            Semantic::Normals,
            &[(DataType::F32, Dimensions::Vec3, None)],
        )?;
        let tangent_count = check(
            Semantic::Tangents,
            &[(DataType::F32, Dimensions::Vec4, None)],
        )?;
        let uv_count = check(
            Semantic::TexCoords(0),
            &[
                (DataType::F32, Dimensions::Vec2, None),
                (DataType::U8, Dimensions::Vec2, Some(true)),
                (DataType::U16, Dimensions::Vec2, Some(true)),
            ],
        )?;
        for (name, c) in [
            ("NORMAL", normal_count),
            ("TANGENT", tangent_count),
            ("TEXCOORD_0", uv_count),
        ] {
            if let Some(c) = c
                && c != count
            {
                return Err(format!(
                    "{what}: {name} has {c} entries but POSITION has {count}"
                ));
            }
        }
        if count == 0 {
            self.acc
                .warnings
                .push(MeshWarning::Note(format!("{what}: no vertices, skipped")));
            return Ok(());
        }
        if let Some(ix) = prim.indices()
            && (ix.count() == 0
                || !matches!(ix.data_type(), DataType::U8 | DataType::U16 | DataType::U32)
                || ix.dimensions() != Dimensions::Scalar)
        {
            return Err(format!(
                "{what}: indices are not unsigned scalars, or empty"
            ));
        }

        let reader = prim.reader(|b| self.buffers.get(b.index()).map(|d| d.0.as_slice()));
        let missing = |attr: &str| format!("{what}: the data of {attr} lies outside its buffer");
        let positions: Vec<Vec3> = reader
            .read_positions()
            .ok_or_else(|| missing("POSITION"))?
            .map(Vec3::from_array)
            .collect();
        let normals: Option<Vec<Vec3>> = normal_count
            .map(|_| {
                let read = reader.read_normals().ok_or_else(|| missing("NORMAL"))?;
                Ok::<_, String>(read.map(Vec3::from_array).collect())
            })
            .transpose()?;
        let tangents: Option<Vec<Vec4>> = tangent_count
            .map(|_| {
                let read = reader.read_tangents().ok_or_else(|| missing("TANGENT"))?;
                Ok::<_, String>(read.map(Vec4::from_array).collect())
            })
            .transpose()?;
        let uvs: Option<Vec<Vec2>> = match uv_count {
            Some(_) => Some(
                reader
                    .read_tex_coords(0)
                    .ok_or_else(|| missing("TEXCOORD_0"))?
                    .into_f32()
                    // glTF's v points down; ours up (docs/models.md §1).
                    .map(|[u, v]| Vec2::new(u, 1.0 - v))
                    .collect(),
            ),
            None => None,
        };
        let n = positions.len();
        let raw_indices: Vec<u32> = match reader.read_indices() {
            Some(ix) => ix.into_u32().collect(),
            None if prim.indices().is_some() => return Err(missing("indices")),
            None => (0..n as u32).collect(),
        };
        let mut tris = triangulate(prim.mode(), &raw_indices);

        let normal_matrix = Mat3::from_mat4(world).inverse().transpose();
        let det = Mat3::from_mat4(world).determinant();
        if det < 0.0 {
            for t in tris.chunks_exact_mut(3) {
                t.swap(1, 2);
            }
        }
        let base = self.acc.positions.len() as u32;
        let first_triangle = (self.acc.indices.len() / 3) as u32;
        self.acc
            .positions
            .extend(positions.iter().map(|&p| world.transform_point3(p)));
        match normals {
            Some(ns) => self.acc.normals.extend(
                ns.iter()
                    .map(|&n| Some((normal_matrix * n).normalize_or_zero())),
            ),
            None => self.acc.normals.extend(std::iter::repeat_n(None, n)),
        }
        match uvs {
            Some(uvs) => self.acc.uvs.extend(uvs.into_iter().map(Some)),
            None => self.acc.uvs.extend(std::iter::repeat_n(None, n)),
        }
        match tangents {
            Some(ts) => self.acc.tangents.extend(ts.iter().map(|t| {
                let xyz = (Mat3::from_mat4(world) * t.truncate()).normalize_or_zero();
                Some(xyz.extend(if det < 0.0 { -t.w } else { t.w }))
            })),
            None => self.acc.tangents.extend(std::iter::repeat_n(None, n)),
        }
        // Out-of-range indices stay out of range (Mesh::build drops and counts them).
        self.acc.indices.extend(
            tris.iter()
                .map(|&i| if (i as usize) < n { base + i } else { u32::MAX }),
        );
        self.acc.parts.push(MeshPart {
            name: what,
            first_triangle,
            triangle_count: (tris.len() / 3) as u32,
        });
        Ok(())
    }
}

/// A triangle list from the indices of a triangle list, strip or fan (glTF §3.7.2.1).
fn triangulate(mode: Mode, ix: &[u32]) -> Vec<u32> {
    match mode {
        Mode::TriangleStrip => (2..ix.len())
            .flat_map(|i| {
                // Every other triangle is reversed to keep a consistent winding.
                if i % 2 == 0 {
                    [ix[i - 2], ix[i - 1], ix[i]]
                } else {
                    [ix[i - 1], ix[i - 2], ix[i]]
                }
            })
            .collect(),
        Mode::TriangleFan => (2..ix.len())
            .flat_map(|i| [ix[0], ix[i - 1], ix[i]])
            .collect(),
        _ => ix[..ix.len() - ix.len() % 3].to_vec(),
    }
}

#[cfg(test)]
#[path = "gltf_tests.rs"]
mod tests;
