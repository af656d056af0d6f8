//! Writing a head as binary glTF 2.0 (GLB): the mesh with its parts, UDIM tiles and
//! morph targets, its materials and their maps embedded, and extra meshes beside it (the
//! aged hair). Read back by [`super::gltf::load`]; written by hand as JSON text and one
//! binary chunk so that the same mesh gives the same bytes.

use glam::Vec3;

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
pub(super) fn push_view(
    bin: &mut Vec<u8>,
    views: &mut Vec<String>,
    bytes: &[u8],
    extra: &str,
) -> usize {
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
    write_glb_with_morph(mesh, materials, &[])
}

/// A morph target of every primitive (glTF `targets`, named in the mesh's
/// `extras.targetNames`, the convention Blender and three.js read as shape keys): per vertex
/// of the mesh, the position, normal and tangent (xyz) deltas, and its default weight in
/// the mesh's `weights`.
#[derive(Clone, Debug, PartialEq)]
pub struct GlbMorph {
    pub name: String,
    pub position: Vec<Vec3>,
    pub normal: Vec<Vec3>,
    pub tangent: Vec<Vec3>,
    pub weight: f32,
}

/// A mesh beside the head (the aged hair): triangles with per-vertex colours (glTF
/// `COLOR_0`, which multiplies the material's base colour), in glTF's units (metres),
/// drawn with its own material, as a node of its own named `name`.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct GlbExtraMesh {
    pub name: String,
    pub positions: Vec<Vec3>,
    pub normals: Vec<Vec3>,
    /// Linear RGBA per vertex, 16-bit (8 bits would band a dark hair's linear colour).
    pub colours: Vec<[u16; 4]>,
    pub indices: Vec<u32>,
    /// Its material: base colour factor, roughness, double-sided.
    pub material_name: String,
    pub roughness: f32,
}

/// [`write_glb_with_materials`] with the morph targets `morphs` (in their order) on every
/// mesh.
pub fn write_glb_with_morph(
    mesh: &super::Mesh,
    materials: &[GlbMaterial],
    morphs: &[GlbMorph],
) -> Vec<u8> {
    write_glb_with_extras(mesh, materials, morphs, &[])
}

/// [`write_glb_with_morph`] with `extras`, meshes of their own beside the head.
pub fn write_glb_with_extras(
    mesh: &super::Mesh,
    materials: &[GlbMaterial],
    morphs: &[GlbMorph],
    extras: &[GlbExtraMesh],
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
            // Each morph target's deltas of this primitive's vertices.
            let mut target = |m: &GlbMorph| {
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
                format!(r#"{{"POSITION":{pos},"NORMAL":{nor},"TANGENT":{tan}}}"#)
            };
            let targets = if morphs.is_empty() {
                String::new()
            } else {
                let t: Vec<String> = morphs.iter().map(&mut target).collect();
                format!(r#","targets":[{}]"#, t.join(","))
            };
            let material = match materials.len() {
                0 => String::new(),
                n if skin => format!(r#","material":{}"#, tile.min(n - 1)),
                _ => format!(r#","material":{plain_material}"#),
            };
            primitives.push(format!(
                r#"{{"attributes":{{"POSITION":{pos},"NORMAL":{nor},"TANGENT":{tan},"TEXCOORD_0":{uv}}},"indices":{ind},"mode":4{material}{targets}}}"#
            ));
        }
        let morph_json = if morphs.is_empty() {
            String::new()
        } else {
            let weights: Vec<String> = morphs
                .iter()
                .map(|m| {
                    let w = if m.weight.is_finite() { m.weight } else { 0.0 };
                    w.to_string()
                })
                .collect();
            let names: Vec<String> = morphs.iter().map(|m| json_string(&m.name)).collect();
            format!(
                r#","weights":[{}],"extras":{{"targetNames":[{}]}}"#,
                weights.join(","),
                names.join(",")
            )
        };
        meshes.push(format!(
            r#"{{"name":{},"primitives":[{}]{morph_json}}}"#,
            json_string(&part.name),
            primitives.join(",")
        ));
    }
    // The meshes beside the head, each with its material after the head's.
    let first_extra_material = materials.len() + usize::from(any_not_skin && !materials.is_empty());
    for (k, extra) in extras.iter().enumerate() {
        let count = extra.positions.len();
        let (bytes, json) = bounded_vec3(&extra.positions);
        let pos = push(&bytes, ARRAY_BUFFER, json);
        let nor = push(
            &f32s(&mut extra.normals.iter().take(count).flat_map(|n| n.to_array())),
            ARRAY_BUFFER,
            format!(r#"{{"bufferView":VIEW,"componentType":5126,"count":{count},"type":"VEC3"}}"#),
        );
        let col = push(
            &extra
                .colours
                .iter()
                .take(count)
                .flatten()
                .flat_map(|c| c.to_le_bytes())
                .collect::<Vec<u8>>(),
            ARRAY_BUFFER,
            format!(
                r#"{{"bufferView":VIEW,"componentType":5123,"normalized":true,"count":{count},"type":"VEC4"}}"#
            ),
        );
        let ix: Vec<u8> = extra.indices.iter().flat_map(|i| i.to_le_bytes()).collect();
        let ind = push(
            &ix,
            ELEMENT_ARRAY_BUFFER,
            format!(
                r#"{{"bufferView":VIEW,"componentType":5125,"count":{},"type":"SCALAR"}}"#,
                extra.indices.len()
            ),
        );
        meshes.push(format!(
            r#"{{"name":{},"primitives":[{{"attributes":{{"POSITION":{pos},"NORMAL":{nor},"COLOR_0":{col}}},"indices":{ind},"mode":4,"material":{}}}]}}"#,
            json_string(&extra.name),
            first_extra_material + k
        ));
    }
    // The materials, and their maps as images in the binary chunk.
    let mut material_json = String::new();
    if !materials.is_empty() || !extras.is_empty() {
        let mut images = Vec::new();
        let mut list = Vec::new();
        // The first material's base colour texture: the parts that are not skin read it
        // too, as the view draws them (an eye drawn on a blank eyeball is in it).
        let mut first_colour = None;
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
                    _ => {
                        first_colour.get_or_insert(index);
                        colour = format!(r#","baseColorTexture":{texture}"#);
                    }
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
        if any_not_skin && !materials.is_empty() {
            let (factor, colour) = first_colour.map_or(("0.9,0.9,0.9", String::new()), |index| {
                (
                    "1,1,1",
                    format!(r#","baseColorTexture":{{"index":{index}}}"#),
                )
            });
            list.push(format!(
                r#"{{"name":"not skin (not aged by agesim; as its view draws it)","pbrMetallicRoughness":{{"baseColorFactor":[{factor},1]{colour},"metallicFactor":0,"roughnessFactor":0.3}}}}"#
            ));
        }
        for extra in extras {
            let r = if extra.roughness.is_finite() {
                extra.roughness.clamp(0.0, 1.0)
            } else {
                0.5
            };
            list.push(format!(
                r#"{{"name":{},"pbrMetallicRoughness":{{"baseColorFactor":[1,1,1,1],"metallicFactor":0,"roughnessFactor":{r}}},"doubleSided":true}}"#,
                json_string(&extra.material_name)
            ));
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
        if let Some(first) = materials.first().filter(|m| !m.extras.is_null()) {
            material_json.push_str(&format!(r#","extras":{}"#, first.extras));
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
        .chain(extras.iter().enumerate().map(|(k, e)| {
            format!(
                r#"{{"name":{},"mesh":{}}}"#,
                json_string(&e.name),
                mesh.parts().len() + k
            )
        }))
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
