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

/// Writes `mesh` as a binary glTF 2.0 file (GLB): one node and mesh per part (named after
/// it), each with one indexed triangle primitive carrying POSITION (with its bounds),
/// NORMAL, TANGENT and TEXCOORD_0 as `f32` and `u32` indices. UV v is flipped to glTF's
/// v-down. Each part gets the vertices it uses, in their order in `mesh`, so that a
/// one-part mesh reads back with the same vertex order, and [`load_bytes`] gives back the
/// same data up to the rounding of the v flip and of normalisation (a few ulps).
/// Deterministic: the same mesh gives the same bytes.
pub fn write_glb(mesh: &super::Mesh) -> Vec<u8> {
    write_glb_with_material(mesh, None)
}

/// A glTF metallic-roughness material for [`write_glb_with_material`].
#[derive(Clone, Debug)]
pub struct GlbMaterial {
    pub name: String,
    /// Linear RGBA (`baseColorFactor`; multiplies `base_colour_png` when there is one).
    pub base_colour: [f32; 4],
    /// The base colour as PNG (or JPEG) bytes (sRGB, over the mesh's UVs), embedded in the
    /// binary chunk as `baseColorTexture`.
    pub base_colour_png: Option<Vec<u8>>,
    pub roughness: f32,
    pub metallic: f32,
    /// A tangent-space normal map as PNG (or JPEG) bytes (OpenGL convention: green = +bitangent, as
    /// glTF 2.0 §3.9.3 asks), embedded in the binary chunk as `normalTexture`.
    pub normal_png: Option<Vec<u8>>,
    /// Occlusion, roughness and metallic as one RGB PNG (red, green, blue: glTF 2.0
    /// §3.9.3's channels), embedded once as both `occlusionTexture` and
    /// `metallicRoughnessTexture`; `roughness` and `metallic` then multiply it (1 keeps
    /// the texture's values).
    pub orm_png: Option<Vec<u8>>,
    /// Recorded in the file's `extras` (glTF has no displacement: a height map beside).
    pub extras: serde_json::Value,
}

/// A float VEC3 accessor of `points` with the `min` and `max` glTF requires of a
/// POSITION (a mesh's and a morph target's): its bytes and its JSON (`VIEW` for the view).
fn bounded_vec3(points: &[Vec3]) -> (Vec<u8>, String) {
    let (lo, hi) = super::Aabb::from_points(points).map_or(([0.0; 3], [0.0; 3]), |b| {
        (b.min.to_array(), b.max.to_array())
    });
    let count = points.len();
    let bytes = points
        .iter()
        .flat_map(|p| p.to_array())
        .flat_map(f32::to_le_bytes)
        .collect();
    let json = format!(
        r#"{{"bufferView":VIEW,"componentType":5126,"count":{count},"type":"VEC3","min":{lo:?},"max":{hi:?}}}"#
    );
    (bytes, json)
}

/// Appends `bytes` to the binary chunk `bin` (4-byte aligned) and a buffer view on them to
/// `views` (`extra`: more members of the view, e.g. `,"target":34962`); returns the view's
/// index.
fn push_view(bin: &mut Vec<u8>, views: &mut Vec<String>, bytes: &[u8], extra: &str) -> usize {
    while !bin.len().is_multiple_of(4) {
        bin.push(0);
    }
    views.push(format!(
        r#"{{"buffer":0,"byteOffset":{},"byteLength":{}{extra}}}"#,
        bin.len(),
        bytes.len()
    ));
    bin.extend_from_slice(bytes);
    views.len() - 1
}

/// [`write_glb`], with every skin primitive using `material` when given.
pub fn write_glb_with_material(mesh: &super::Mesh, material: Option<&GlbMaterial>) -> Vec<u8> {
    write_glb_with_materials(mesh, material.map(std::slice::from_ref).unwrap_or_default())
}

/// [`write_glb`] with the skin's `materials`, one per UDIM tile of the mesh
/// ([`super::Mesh::udim`]; one for a single-tile layout): a multi-tile head's skin is one
/// primitive per tile, its UVs in [0, 1] as the tile's own maps are (glTF has no UDIM).
/// Parts that are not skin get a plain material of their own.
pub fn write_glb_with_materials(mesh: &super::Mesh, materials: &[GlbMaterial]) -> Vec<u8> {
    write_glb_with_morph(mesh, materials, None)
}

/// A morph target of every primitive (glTF `targets`, named in the mesh's
/// `extras.targetNames`, the convention Blender and three.js read as shape keys): per vertex
/// of the mesh, the position, normal and tangent (xyz) deltas, and the mesh's default
/// weight.
#[derive(Clone, Debug, PartialEq)]
pub struct GlbMorph {
    pub name: String,
    pub position: Vec<Vec3>,
    pub normal: Vec<Vec3>,
    pub tangent: Vec<Vec3>,
    pub weight: f32,
}

/// [`write_glb_with_materials`] with a morph target on every mesh.
pub fn write_glb_with_morph(
    mesh: &super::Mesh,
    materials: &[GlbMaterial],
    morph: Option<&GlbMorph>,
) -> Vec<u8> {
    let mut bin: Vec<u8> = Vec::new();
    let mut views = Vec::new();
    let mut accessors = Vec::new();
    let mut meshes = Vec::new();
    // Appends `bytes` as a buffer view (4-byte aligned) and an accessor on it.
    let mut push = |bytes: &[u8], target: u32, accessor: String| {
        let view = push_view(
            &mut bin,
            &mut views,
            bytes,
            &format!(r#","target":{target}"#),
        );
        accessors.push(accessor.replace("VIEW", &view.to_string()));
        accessors.len() - 1
    };
    let f32s =
        |v: &mut dyn Iterator<Item = f32>| -> Vec<u8> { v.flat_map(f32::to_le_bytes).collect() };
    const ARRAY_BUFFER: u32 = 34962;
    const ELEMENT_ARRAY_BUFFER: u32 = 34963;
    // Parts that are not skin (eyes, teeth…) get a plain material of their own: our maps
    // are the skin's.
    let any_not_skin = mesh
        .parts()
        .iter()
        .enumerate()
        .any(|(k, p)| !mesh.part_is_skin(k, p));
    let plain_material = materials.len();
    // UVs as each tile's maps read them: a UDIM head's atlas cell back to [0, 1].
    let triangle_tiles = mesh.triangle_tiles();
    let local_uv = |i: usize, tile: usize| match mesh.udim() {
        Some(u) => mesh.uvs()[i] * u.grid() as f32 - u.cell(tile).as_vec2(),
        None => mesh.uvs()[i],
    };
    let tiles = mesh.udim().map_or(1, |u| u.tiles().len());
    for (k, part) in mesh.parts().iter().enumerate() {
        let first = part.first_triangle as usize;
        let count = part.triangle_count as usize;
        let skin = mesh.part_is_skin(k, part);
        let mut primitives = Vec::new();
        for tile in 0..tiles {
            let tri: Vec<u32> = (first..first + count)
                .filter(|&t| triangle_tiles[t] == tile)
                .flat_map(|t| mesh.indices()[t * 3..t * 3 + 3].iter().copied())
                .collect();
            if tri.is_empty() {
                continue;
            }
            let mut used = vec![false; mesh.vertex_count()];
            for &i in &tri {
                used[i as usize] = true;
            }
            let mut remap = vec![0u32; mesh.vertex_count()];
            let mut verts = Vec::new();
            for (i, &u) in used.iter().enumerate() {
                if u {
                    remap[i] = verts.len() as u32;
                    verts.push(i);
                }
            }
            let count = verts.len();
            let positions: Vec<Vec3> = verts.iter().map(|&i| mesh.positions()[i]).collect();
            let vec = |ty: &str| {
                format!(
                    r#"{{"bufferView":VIEW,"componentType":5126,"count":{count},"type":"{ty}"}}"#
                )
            };
            let (bytes, json) = bounded_vec3(&positions);
            let pos = push(&bytes, ARRAY_BUFFER, json);
            let nor = push(
                &f32s(&mut verts.iter().flat_map(|&i| mesh.normals()[i].to_array())),
                ARRAY_BUFFER,
                vec("VEC3"),
            );
            let tan = push(
                &f32s(&mut verts.iter().flat_map(|&i| mesh.tangents()[i].to_array())),
                ARRAY_BUFFER,
                vec("VEC4"),
            );
            let uv = push(
                &f32s(&mut verts.iter().flat_map(|&i| {
                    let uv = local_uv(i, tile);
                    [uv.x, 1.0 - uv.y]
                })),
                ARRAY_BUFFER,
                vec("VEC2"),
            );
            let ix: Vec<u8> = tri
                .iter()
                .flat_map(|&i| remap[i as usize].to_le_bytes())
                .collect();
            let ind = push(
                &ix,
                ELEMENT_ARRAY_BUFFER,
                format!(
                    r#"{{"bufferView":VIEW,"componentType":5125,"count":{},"type":"SCALAR"}}"#,
                    tri.len()
                ),
            );
            // The morph target's deltas of this primitive's vertices.
            let targets = morph.map_or(String::new(), |m| {
                let at = |v: &[Vec3], i: usize| v.get(i).copied().unwrap_or(Vec3::ZERO);
                let dp: Vec<Vec3> = verts.iter().map(|&i| at(&m.position, i)).collect();
                let (bytes, json) = bounded_vec3(&dp);
                let pos = push(&bytes, ARRAY_BUFFER, json);
                let nor = push(
                    &f32s(&mut verts.iter().flat_map(|&i| at(&m.normal, i).to_array())),
                    ARRAY_BUFFER,
                    vec("VEC3"),
                );
                let tan = push(
                    &f32s(&mut verts.iter().flat_map(|&i| at(&m.tangent, i).to_array())),
                    ARRAY_BUFFER,
                    vec("VEC3"),
                );
                format!(r#","targets":[{{"POSITION":{pos},"NORMAL":{nor},"TANGENT":{tan}}}]"#)
            });
            let material = match materials.len() {
                0 => String::new(),
                n if skin => format!(r#","material":{}"#, tile.min(n - 1)),
                _ => format!(r#","material":{plain_material}"#),
            };
            primitives.push(format!(
                r#"{{"attributes":{{"POSITION":{pos},"NORMAL":{nor},"TANGENT":{tan},"TEXCOORD_0":{uv}}},"indices":{ind},"mode":4{material}{targets}}}"#
            ));
        }
        let morph_json = morph.map_or(String::new(), |m| {
            let w = if m.weight.is_finite() { m.weight } else { 0.0 };
            format!(
                r#","weights":[{w}],"extras":{{"targetNames":[{}]}}"#,
                json_string(&m.name)
            )
        });
        meshes.push(format!(
            r#"{{"name":{},"primitives":[{}]{morph_json}}}"#,
            json_string(&part.name),
            primitives.join(",")
        ));
    }
    // The materials, and their maps as images in the binary chunk.
    let mut material_json = String::new();
    if !materials.is_empty() {
        let mut images = Vec::new();
        let mut list = Vec::new();
        for m in materials {
            let mut normal = String::new();
            let mut colour = String::new();
            let mut occlusion = String::new();
            let mut metallic_roughness = String::new();
            for (png, name) in [
                (&m.normal_png, "normal"),
                (&m.base_colour_png, "base colour"),
                (&m.orm_png, "occlusion, roughness, metallic"),
            ] {
                let Some(png) = png else { continue };
                let view = push_view(&mut bin, &mut views, png, "");
                let index = images.len();
                // JPEG bytes (the default head's scanned maps) are embedded as they are.
                let mime = if png.starts_with(&[0xFF, 0xD8]) {
                    "image/jpeg"
                } else {
                    "image/png"
                };
                images.push(format!(
                    r#"{{"bufferView":{view},"mimeType":"{mime}","name":{}}}"#,
                    json_string(&format!("{name}, {}", m.name))
                ));
                let texture = format!(r#"{{"index":{index}}}"#);
                match name {
                    "normal" => normal = format!(r#","normalTexture":{texture}"#),
                    "occlusion, roughness, metallic" => {
                        occlusion = format!(r#","occlusionTexture":{texture}"#);
                        metallic_roughness = format!(r#","metallicRoughnessTexture":{texture}"#);
                    }
                    _ => colour = format!(r#","baseColorTexture":{texture}"#),
                }
            }
            let f = |x: f32| if x.is_finite() { x } else { 0.0 };
            let [r, g, b, a] = m.base_colour.map(f);
            let extras = if m.extras.is_null() {
                String::new()
            } else {
                format!(r#","extras":{}"#, m.extras)
            };
            list.push(format!(
                r#"{{"name":{},"pbrMetallicRoughness":{{"baseColorFactor":[{r},{g},{b},{a}]{colour},"metallicFactor":{},"roughnessFactor":{}{metallic_roughness}}}{normal}{occlusion}{extras}}}"#,
                json_string(&m.name),
                f(m.metallic),
                f(m.roughness),
            ));
        }
        if any_not_skin {
            list.push(r#"{"name":"not skin (left as it is by agesim)","pbrMetallicRoughness":{"baseColorFactor":[0.9,0.9,0.9,1],"metallicFactor":0,"roughnessFactor":0.3}}"#.to_owned());
        }
        let images = if images.is_empty() {
            String::new()
        } else {
            let textures: Vec<String> = (0..images.len())
                .map(|i| format!(r#"{{"source":{i},"sampler":0}}"#))
                .collect();
            format!(
                r#","images":[{}],"textures":[{}],"samplers":[{{"magFilter":9729,"minFilter":9987,"wrapS":33071,"wrapT":33071}}]"#,
                images.join(","),
                textures.join(",")
            )
        };
        material_json = format!(r#","materials":[{}]{images}"#, list.join(","));
        // The first material's extras also describe the file (readers that show the
        // asset's extras).
        if !materials[0].extras.is_null() {
            material_json.push_str(&format!(r#","extras":{}"#, materials[0].extras));
        }
    }
    while !bin.len().is_multiple_of(4) {
        bin.push(0);
    }
    let nodes: Vec<String> = mesh
        .parts()
        .iter()
        .enumerate()
        .map(|(k, p)| format!(r#"{{"name":{},"mesh":{k}}}"#, json_string(&p.name)))
        .collect();
    let scene_nodes: Vec<String> = (0..nodes.len()).map(|k| k.to_string()).collect();
    let json = format!(
        r#"{{"asset":{{"version":"2.0","generator":"agesim"}},"scene":0,"scenes":[{{"nodes":[{}]}}],"nodes":[{}],"meshes":[{}],"accessors":[{}],"bufferViews":[{}],"buffers":[{{"byteLength":{}}}]{material_json}}}"#,
        scene_nodes.join(","),
        nodes.join(","),
        meshes.join(","),
        accessors.join(","),
        views.join(","),
        bin.len()
    )
    .into_bytes();
    glb_container(&json, &bin)
}

/// A GLB file of a JSON chunk and a binary chunk (each padded to 4 bytes: the JSON with
/// spaces, the binary with zeros), lengths written as they are.
pub fn glb_container(json: &[u8], bin: &[u8]) -> Vec<u8> {
    let pad = |v: &[u8], with: u8| {
        let mut v = v.to_vec();
        while !v.len().is_multiple_of(4) {
            v.push(with);
        }
        v
    };
    let (json, bin) = (pad(json, b' '), pad(bin, 0));
    let total = 12 + 8 + json.len() + 8 + bin.len();
    let mut out = Vec::with_capacity(total);
    out.extend_from_slice(b"glTF");
    out.extend_from_slice(&2u32.to_le_bytes());
    out.extend_from_slice(&(total as u32).to_le_bytes());
    out.extend_from_slice(&(json.len() as u32).to_le_bytes());
    out.extend_from_slice(b"JSON");
    out.extend_from_slice(&json);
    out.extend_from_slice(&(bin.len() as u32).to_le_bytes());
    out.extend_from_slice(b"BIN\0");
    out.extend_from_slice(&bin);
    out
}

/// `s` as a JSON string literal.
fn json_string(s: &str) -> String {
    serde_json::Value::String(s.to_owned()).to_string()
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
mod tests {
    //! Fixtures are written by the tests: small glTF files with `data:` buffers, an
    //! external `.bin`, and a GLB.
    use super::*;
    use crate::head::mesh::test_util::{assert_close, assert_vec_close};
    use crate::head::mesh::{Mesh, TangentSource};

    /// One primitive's data for a fixture.
    struct Prim {
        positions: Vec<[f32; 3]>,
        normals: Option<Vec<[f32; 3]>>,
        uvs: Option<Vec<[f32; 2]>>,
        indices: Vec<u16>,
    }

    fn quad_prim(normals: bool, uvs: bool) -> Prim {
        Prim {
            positions: vec![
                [0.0, 0.0, 0.0],
                [1.0, 0.0, 0.0],
                [1.0, 1.0, 0.0],
                [0.0, 1.0, 0.0],
            ],
            normals: normals.then(|| vec![[0.0, 0.0, 1.0]; 4]),
            // glTF v down: the top edge (y = 1) has v = 0.
            uvs: uvs.then(|| vec![[0.0, 1.0], [1.0, 1.0], [1.0, 0.0], [0.0, 0.0]]),
            indices: vec![0, 1, 2, 0, 2, 3],
        }
    }

    /// Builds the JSON (and the binary buffer) of a file with one mesh per entry of
    /// `meshes` (each a list of primitives) and the given `nodes` JSON.
    fn fixture(meshes: &[Vec<Prim>], nodes: &str) -> (String, Vec<u8>) {
        let mut bin = Vec::new();
        let mut views = Vec::new();
        let mut accessors = Vec::new();
        // One buffer view and its accessor: `kind` is the accessor's componentType, type
        // and count (and bounds), `VIEW` standing for the view's index.
        let mut push = |bytes: &[u8], kind: String| {
            let view = super::push_view(&mut bin, &mut views, bytes, "");
            accessors.push(format!(r#"{{"bufferView":{view},{kind}}}"#));
            accessors.len() - 1
        };
        let floats = |count: usize, ty: &str| {
            format!(r#""componentType":5126,"count":{count},"type":"{ty}""#)
        };
        let mut mesh_json = Vec::new();
        for prims in meshes {
            let mut prim_json = Vec::new();
            for p in prims {
                let mut attrs = Vec::new();
                let (lo, hi) =
                    p.positions
                        .iter()
                        .fold(([f32::MAX; 3], [f32::MIN; 3]), |(lo, hi), q| {
                            (
                                [lo[0].min(q[0]), lo[1].min(q[1]), lo[2].min(q[2])],
                                [hi[0].max(q[0]), hi[1].max(q[1]), hi[2].max(q[2])],
                            )
                        });
                let bounds = format!(r#","min":{lo:?},"max":{hi:?}"#);
                let a = push(
                    bytemuck::cast_slice(&p.positions),
                    floats(p.positions.len(), "VEC3") + &bounds,
                );
                attrs.push(format!(r#""POSITION":{a}"#));
                if let Some(n) = &p.normals {
                    let a = push(bytemuck::cast_slice(n), floats(n.len(), "VEC3"));
                    attrs.push(format!(r#""NORMAL":{a}"#));
                }
                if let Some(t) = &p.uvs {
                    let a = push(bytemuck::cast_slice(t), floats(t.len(), "VEC2"));
                    attrs.push(format!(r#""TEXCOORD_0":{a}"#));
                }
                let i = push(
                    bytemuck::cast_slice(&p.indices),
                    format!(
                        r#""componentType":5123,"count":{},"type":"SCALAR""#,
                        p.indices.len()
                    ),
                );
                prim_json.push(format!(
                    r#"{{"attributes":{{{}}},"indices":{i}}}"#,
                    attrs.join(",")
                ));
            }
            mesh_json.push(format!(
                r#"{{"name":"m{}","primitives":[{}]}}"#,
                mesh_json.len(),
                prim_json.join(",")
            ));
        }
        while !bin.len().is_multiple_of(4) {
            bin.push(0);
        }
        let json = format!(
            r#"{{"asset":{{"version":"2.0"}},"scene":0,"scenes":[{{"nodes":[0]}}],"nodes":{nodes},"meshes":[{}],"accessors":[{}],"bufferViews":[{}],"buffers":[{{"byteLength":{},"uri":"URI"}}]}}"#,
            mesh_json.join(","),
            accessors.join(","),
            views.join(","),
            bin.len()
        );
        (json, bin)
    }

    fn base64(bytes: &[u8]) -> String {
        const A: &[u8; 64] = b"ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
        let mut out = String::new();
        for c in bytes.chunks(3) {
            let b = [c[0], *c.get(1).unwrap_or(&0), *c.get(2).unwrap_or(&0)];
            let n = (b[0] as u32) << 16 | (b[1] as u32) << 8 | b[2] as u32;
            for k in 0..4 {
                if k <= c.len() {
                    out.push(A[(n >> (18 - 6 * k) & 63) as usize] as char);
                } else {
                    out.push('=');
                }
            }
        }
        out
    }

    fn write_embedded(dir: &Path, name: &str, json: &str, bin: &[u8]) -> std::path::PathBuf {
        let path = dir.join(name);
        let uri = format!("data:application/octet-stream;base64,{}", base64(bin));
        std::fs::write(&path, json.replace("URI", &uri)).unwrap();
        path
    }

    fn write_glb(dir: &Path, name: &str, json: &str, bin: &[u8]) -> std::path::PathBuf {
        // GLB: the buffer has no uri.
        let mut json = json.replace(r#","uri":"URI""#, "").into_bytes();
        while !json.len().is_multiple_of(4) {
            json.push(b' ');
        }
        let total = 12 + 8 + json.len() + 8 + bin.len();
        let mut out = Vec::new();
        out.extend_from_slice(b"glTF");
        out.extend_from_slice(&2u32.to_le_bytes());
        out.extend_from_slice(&(total as u32).to_le_bytes());
        out.extend_from_slice(&(json.len() as u32).to_le_bytes());
        out.extend_from_slice(b"JSON");
        out.extend_from_slice(&json);
        out.extend_from_slice(&(bin.len() as u32).to_le_bytes());
        out.extend_from_slice(b"BIN\0");
        out.extend_from_slice(bin);
        let path = dir.join(name);
        std::fs::write(&path, out).unwrap();
        path
    }

    /// Two meshes: "m0" with two primitives (a quad with normals and UVs, a quad with
    /// UVs only), "m1" one quad; node 0 translates by (10, 0, 0) and has a child scaling
    /// by 2 that holds m1.
    fn two_level_fixture() -> (String, Vec<u8>) {
        fixture(
            &[
                vec![quad_prim(true, true), quad_prim(false, true)],
                vec![quad_prim(true, true)],
            ],
            r#"[{"name":"root","mesh":0,"translation":[10,0,0],"children":[1]},{"name":"child","mesh":1,"scale":[2,2,2]}]"#,
        )
    }

    fn check_two_level(m: &Mesh) {
        assert_eq!(m.triangle_count(), 6);
        assert_eq!(m.parts().len(), 3, "{:?}", m.parts());
        assert!(
            m.parts()[0].name.contains("m0") && m.parts()[0].name.contains("root"),
            "{:?}",
            m.parts()
        );
        assert!(m.parts()[2].name.contains("child"));
        // Node transforms: m0 at x ∈ [10, 11]; m1 under translate·scale at x ∈ [10, 12].
        assert_vec_close(m.bounds().min, Vec3::new(10.0, 0.0, 0.0), 1e-6, "min");
        assert_vec_close(m.bounds().max, Vec3::new(12.0, 2.0, 0.0), 1e-6, "max");
        // v flipped: the vertex at y = 1 of the first quad (glTF v = 0) has v = 1.
        for part in m.parts() {
            let scale = if part.name.contains("child") {
                2.0
            } else {
                1.0
            };
            let first = part.first_triangle as usize * 3;
            for &v in &m.indices()[first..first + part.triangle_count as usize * 3] {
                let (p, uv) = (m.positions()[v as usize], m.uvs()[v as usize]);
                assert_close(uv.y, p.y / scale, 1e-6, "v up");
            }
        }
        // The primitive without normals got computed ones; all face +z.
        for n in m.normals() {
            assert_vec_close(*n, Vec3::Z, 1e-6, "normal");
        }
        assert!(!m.report().uvs_generated);
        assert_eq!(m.report().tangent_source, Some(TangentSource::MikkTSpace));
        for t in m.tangents() {
            assert_vec_close(t.truncate(), Vec3::X, 1e-5, "tangent");
        }
    }

    #[test]
    fn write_glb_reads_back_the_same_mesh_part_by_part() {
        // Two parts sharing the middle edge (vertices 1 and 4); part 1 is the right quad.
        let positions = vec![
            Vec3::new(0.0, 0.0, 0.0),
            Vec3::new(1.0, 0.0, 0.0),
            Vec3::new(2.0, 0.0, 0.5),
            Vec3::new(0.0, 1.0, 0.0),
            Vec3::new(1.0, 1.0, 0.0),
            Vec3::new(2.0, 1.0, 0.5),
        ];
        let uvs = positions
            .iter()
            .map(|p| Vec2::new(0.3 * p.x, 0.7 * p.y + 0.1))
            .collect();
        let raw = RawMesh {
            positions,
            uvs: Some(uvs),
            indices: vec![0, 1, 4, 0, 4, 3, 1, 2, 5, 1, 5, 4],
            parts: vec![
                MeshPart {
                    name: "left \"L\"".to_owned(),
                    first_triangle: 0,
                    triangle_count: 2,
                },
                MeshPart {
                    name: "right".to_owned(),
                    first_triangle: 2,
                    triangle_count: 2,
                },
            ],
            ..RawMesh::default()
        };
        let original = Mesh::build(raw, "two quads").unwrap();
        let glb = super::write_glb(&original);
        assert_eq!(&glb[..4], b"glTF");
        assert_eq!(glb, super::write_glb(&original), "deterministic");
        let back = Mesh::build(load_bytes(&glb, Path::new("x.glb")).unwrap(), "x.glb").unwrap();
        assert!(
            back.report().warnings.is_empty(),
            "{:?}",
            back.report().warnings
        );
        assert_eq!(back.report().tangent_source, Some(TangentSource::File));
        assert_eq!(back.parts().len(), 2);
        assert!(
            back.parts()[0].name.contains(r#""left "L"""#),
            "{:?}",
            back.parts()
        );
        // Each part carries its own vertices: the shared edge is written twice.
        assert_eq!(back.vertex_count(), 8);
        assert_eq!(back.triangle_count(), original.triangle_count());
        for (a, b) in original.indices().iter().zip(back.indices()) {
            let (a, b) = (*a as usize, *b as usize);
            assert_vec_close(
                original.positions()[a],
                back.positions()[b],
                0.0,
                "position",
            );
            assert_vec_close(original.normals()[a], back.normals()[b], 1e-6, "normal");
            let (ta, tb) = (original.tangents()[a], back.tangents()[b]);
            assert_vec_close(ta.truncate(), tb.truncate(), 1e-6, "tangent");
            assert_close(ta.w, tb.w, 0.0, "handedness");
            let (ua, ub) = (original.uvs()[a], back.uvs()[b]);
            assert_close(ua.x, ub.x, 0.0, "u");
            assert_close(ua.y, ub.y, 1e-6, "v (flipped twice)");
        }
    }

    #[test]
    fn a_material_with_an_embedded_normal_map_is_valid_gltf() {
        let original = crate::head::mesh::Mesh::build(
            RawMesh {
                positions: vec![Vec3::ZERO, Vec3::X, Vec3::Y],
                uvs: Some(vec![Vec2::ZERO, Vec2::X, Vec2::Y]),
                indices: vec![0, 1, 2],
                ..RawMesh::default()
            },
            "triangle",
        )
        .unwrap();
        // A 1×1 PNG: the importer only needs valid bytes in the chunk.
        let mut png = Vec::new();
        image::RgbImage::from_pixel(1, 1, image::Rgb([128, 128, 255]))
            .write_to(&mut std::io::Cursor::new(&mut png), image::ImageFormat::Png)
            .unwrap();
        let material = GlbMaterial {
            name: "aged skin".into(),
            base_colour: [0.6, 0.4, 0.3, 1.0],
            base_colour_png: None,
            roughness: 0.45,
            metallic: 0.0,
            normal_png: Some(png.clone()),
            orm_png: None,
            extras: serde_json::json!({"age_years": 70.0}),
        };
        let glb = write_glb_with_material(&original, Some(&material));
        let gltf = ::gltf::Gltf::from_slice(&glb).expect("a valid GLB");
        let m = gltf.materials().next().expect("one material");
        assert_eq!(m.name(), Some("aged skin"));
        let pbr = m.pbr_metallic_roughness();
        assert_eq!(pbr.base_color_factor(), [0.6, 0.4, 0.3, 1.0]);
        assert_eq!(pbr.roughness_factor(), 0.45);
        let normal = m.normal_texture().expect("a normal texture");
        let ::gltf::image::Source::View { view, mime_type } = normal.texture().source().source()
        else {
            panic!("the image is embedded");
        };
        assert_eq!(mime_type, "image/png");
        let blob = gltf.blob.as_deref().unwrap();
        let start = view.offset();
        assert_eq!(&blob[start..start + view.length()], png.as_slice());
        let prim = gltf.meshes().next().unwrap().primitives().next().unwrap();
        assert_eq!(prim.material().index(), Some(0));
        assert!(prim.get(&::gltf::Semantic::Tangents).is_some());
        assert_eq!(gltf.materials().count(), 1, "all skin: one material");
        // And it still loads as a mesh.
        load_bytes(&glb, Path::new("x.glb")).unwrap();

        // A part that is not skin (an eye) gets a plain material, without our maps.
        let two = Mesh::load(Path::new(concat!(
            env!("CARGO_MANIFEST_DIR"),
            "/../../assets/heads/makehuman/mh_head.obj"
        )))
        .unwrap();
        let glb = write_glb_with_material(&two, Some(&material));
        let gltf = ::gltf::Gltf::from_slice(&glb).expect("a valid GLB");
        assert_eq!(gltf.materials().count(), 2);
        for (k, mesh) in gltf.meshes().enumerate() {
            let prim = mesh.primitives().next().unwrap();
            let skin = two.part_is_skin(k, &two.parts()[k]);
            assert_eq!(
                prim.material().index(),
                Some(usize::from(!skin)),
                "{:?}",
                mesh.name()
            );
            assert_eq!(prim.material().normal_texture().is_some(), skin);
        }
    }

    #[test]
    fn embedded_buffers_several_primitives_node_transforms_and_v_flip() {
        let dir = tempfile::tempdir().unwrap();
        let (json, bin) = two_level_fixture();
        let m = Mesh::load(&write_embedded(dir.path(), "a.gltf", &json, &bin)).unwrap();
        check_two_level(&m);
        assert!(
            m.report()
                .warnings
                .iter()
                .any(|w| matches!(w, MeshWarning::BadNormalsReplaced(4))),
            "the normals of the second primitive were computed: {:?}",
            m.report().warnings
        );
    }

    #[test]
    fn glb_and_external_buffers_load_the_same() {
        let dir = tempfile::tempdir().unwrap();
        let (json, bin) = two_level_fixture();
        let glb = Mesh::load(&write_glb(dir.path(), "a.glb", &json, &bin)).unwrap();
        check_two_level(&glb);
        std::fs::write(dir.path().join("a.bin"), &bin).unwrap();
        let path = dir.path().join("b.gltf");
        std::fs::write(&path, json.replace("URI", "a.bin")).unwrap();
        let ext = Mesh::load(&path).unwrap();
        assert_eq!(ext.positions(), glb.positions());
        // A missing external buffer is an error naming the file.
        std::fs::remove_file(dir.path().join("a.bin")).unwrap();
        let err = Mesh::load(&path).unwrap_err().to_string();
        assert!(err.contains("b.gltf") && err.contains("buffer"), "{err}");
    }

    #[test]
    fn without_normals_and_uvs_both_are_generated() {
        let dir = tempfile::tempdir().unwrap();
        let (json, bin) = fixture(&[vec![quad_prim(false, false)]], r#"[{"mesh":0}]"#);
        let m = Mesh::load(&write_embedded(dir.path(), "bare.gltf", &json, &bin)).unwrap();
        assert!(m.report().normals_generated && m.report().uvs_generated);
        assert!(m.uvs().iter().all(|uv| uv.is_finite()));
    }

    #[test]
    fn a_mirroring_node_keeps_faces_outward() {
        let dir = tempfile::tempdir().unwrap();
        let (json, bin) = fixture(
            &[vec![quad_prim(true, true)]],
            r#"[{"mesh":0,"scale":[-1,1,1]}]"#,
        );
        let m = Mesh::load(&write_embedded(dir.path(), "mirror.gltf", &json, &bin)).unwrap();
        for t in m.triangles() {
            let [a, b, c] = t.map(|i| m.positions()[i as usize]);
            assert!(
                (b - a).cross(c - a).z > 0.0,
                "winding flipped back to face +z"
            );
        }
        for n in m.normals() {
            assert_vec_close(*n, Vec3::Z, 1e-6, "normal");
        }
        // u now runs along −x: the tangent follows it, handedness flips.
        for t in m.tangents() {
            assert_vec_close(t.truncate(), Vec3::NEG_X, 1e-5, "tangent");
            assert_close(t.w, -1.0, 0.0, "w");
        }
    }

    #[test]
    fn quantized_positions_are_refused_clearly() {
        let dir = tempfile::tempdir().unwrap();
        let (json, bin) = fixture(&[vec![quad_prim(true, true)]], r#"[{"mesh":0}]"#);
        // Re-type the position accessor as normalized shorts (KHR_mesh_quantization).
        let json = json.replacen(
            r#""componentType":5126,"count":4,"type":"VEC3""#,
            r#""componentType":5122,"normalized":true,"count":4,"type":"VEC3""#,
            1,
        );
        let err = Mesh::load(&write_embedded(dir.path(), "q.gltf", &json, &bin))
            .unwrap_err()
            .to_string();
        assert!(
            err.contains("KHR_mesh_quantization") && err.contains("Positions"),
            "{err}"
        );
    }

    #[test]
    fn out_of_range_indices_are_dropped_and_the_rest_kept() {
        let dir = tempfile::tempdir().unwrap();
        let mut prim = quad_prim(true, true);
        prim.indices = vec![0, 1, 2, 0, 2, 9];
        let (json, bin) = fixture(&[vec![prim]], r#"[{"mesh":0}]"#);
        let m = Mesh::load(&write_embedded(dir.path(), "oob.gltf", &json, &bin)).unwrap();
        assert_eq!(m.triangle_count(), 1);
        assert!(
            m.report()
                .warnings
                .contains(&MeshWarning::OutOfRangeTriangles(1))
        );
    }

    #[test]
    fn buffer_uris_outside_the_folder_are_refused() {
        for (uri, ok) in [
            ("data:application/octet-stream;base64,AAAA", true),
            ("mesh.bin", true),
            ("sub/mesh%20a.bin", true),
            ("../../../../etc/passwd", false),
            ("sub/../../x.bin", false),
            ("%2e%2e/x.bin", false),
            ("/etc/passwd", false),
            ("file:///etc/passwd", false),
            ("C:\\x.bin", false),
        ] {
            assert_eq!(check_uri(uri).is_ok(), ok, "{uri}");
        }
        let dir = tempfile::tempdir().unwrap();
        let path = dir.path().join("escape.gltf");
        std::fs::write(
            &path,
            r#"{"asset":{"version":"2.0"},"buffers":[{"byteLength":4,"uri":"../../../../etc/passwd"}]}"#,
        )
        .unwrap();
        let e = load(&path).unwrap_err().to_string();
        assert!(e.contains("escape.gltf") && e.contains("climbs out"), "{e}");
    }

    #[test]
    fn garbage_is_an_error_not_a_panic() {
        let dir = tempfile::tempdir().unwrap();
        let path = dir.path().join("x.glb");
        std::fs::write(&path, b"glTF\x02\0\0\0garbage").unwrap();
        assert!(Mesh::load(&path).is_err());
        let path = dir.path().join("x.gltf");
        std::fs::write(&path, b"{}").unwrap();
        assert!(Mesh::load(&path).is_err());
    }

    #[test]
    fn strips_and_fans_become_lists() {
        assert_eq!(
            triangulate(Mode::TriangleStrip, &[0, 1, 2, 3]),
            vec![0, 1, 2, 2, 1, 3]
        );
        assert_eq!(
            triangulate(Mode::TriangleFan, &[0, 1, 2, 3]),
            vec![0, 1, 2, 0, 2, 3]
        );
        assert_eq!(triangulate(Mode::Triangles, &[0, 1, 2, 3]), vec![0, 1, 2]);
    }
}
