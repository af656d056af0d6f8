//! A head file's own pictures: the base colour and normal maps its material names (glTF
//! `baseColorTexture` and `normalTexture`, embedded or beside the file; OBJ `map_Kd` and
//! `norm` of its `mtllib`), so an imported head keeps its texture work without being
//! told (docs/models.md §7a). Files are read only from the head's own folder, as its
//! buffers are.

use std::path::{Path, PathBuf};

use crate::base::error::Error;
use crate::maps::mask::{Encoding, HeadImage};

/// The pictures a head file's material names, decoded.
#[derive(Clone, Debug, Default)]
pub struct MeshTextures {
    pub colour: Option<std::sync::Arc<HeadImage>>,
    pub normal: Option<std::sync::Arc<HeadImage>>,
    /// Where each came from, for reports.
    pub sources: Vec<String>,
    /// The picture files read (beside the head file; not the embedded ones): a change to
    /// one is a change to the head.
    pub files: Vec<PathBuf>,
}

/// One picture a material names.
enum Source {
    Bytes(Vec<u8>, String),
    File(PathBuf),
}

impl Source {
    fn decode(self, encoding: Encoding) -> Result<(HeadImage, String), Error> {
        match self {
            Source::Bytes(bytes, name) => {
                let image = HeadImage::decode_as(&bytes, Path::new(&name), encoding)?;
                Ok((image, name))
            }
            Source::File(path) => {
                let image = HeadImage::load_as(&path, false, encoding)?;
                Ok((image, path.display().to_string()))
            }
        }
    }
}

/// The base colour and normal maps `path`'s material names (the material of the most
/// triangles that has a base colour map, for glTF); none for other formats or none
/// named. An unreadable picture is an error naming it.
pub fn load(path: &Path) -> Result<MeshTextures, Error> {
    load_tiled(path, None)
}

/// [`load`] for a head with a UDIM layout: a picture file named for one tile
/// (`skin.1001.png`, or `skin.<UDIM>.png`) is read for every tile the head uses and laid
/// out in the head's atlas ([`super::udim`]), as its UVs are.
pub fn load_tiled(path: &Path, udim: Option<&super::udim::Udim>) -> Result<MeshTextures, Error> {
    let ext = path
        .extension()
        .map(|e| e.to_string_lossy().to_lowercase())
        .unwrap_or_default();
    let (colour, normal) = match ext.as_str() {
        // The `gltf` crate unwraps an image's fields the file may lack (a view without a
        // MIME type, no URI): a malformed file is an error, never a crash.
        "gltf" | "glb" => match std::panic::catch_unwind(|| gltf_sources(path)) {
            Ok(found) => found?,
            Err(_) => {
                return Err(Error::MeshFile {
                    path: path.to_owned(),
                    message: "its material names an image the file does not describe fully (a buffer view without a MIME type, or no URI)".into(),
                });
            }
        },
        "obj" => obj_sources(path)?,
        _ => (None, None),
    };
    match udim {
        Some(u) => decode_tiled(colour, normal, u),
        None => decode(colour, normal),
    }
}

/// Decodes the pictures found, noting the files among them.
fn decode(colour: Option<Source>, normal: Option<Source>) -> Result<MeshTextures, Error> {
    let mut out = MeshTextures::default();
    for s in [&colour, &normal].into_iter().flatten() {
        if let Source::File(p) = s {
            out.files.push(p.clone());
        }
    }
    if let Some(s) = colour {
        let (image, name) = s.decode(Encoding::Colour)?;
        out.colour = Some(std::sync::Arc::new(image));
        out.sources.push(format!("colour map {name}"));
    }
    if let Some(s) = normal {
        let (image, name) = s.decode(Encoding::Data)?;
        out.normal = Some(std::sync::Arc::new(image));
        out.sources.push(format!("normal map {name}"));
    }
    Ok(out)
}

/// The tile files of `path` when its name marks a tile (`<UDIM>`, or a number of one of
/// `udim`'s tiles); `None` for a picture of the whole layout.
fn tile_files(path: &Path, udim: &super::udim::Udim) -> Option<Vec<PathBuf>> {
    let name = path.file_name()?.to_string_lossy().into_owned();
    let numbers = udim.numbers();
    let pattern = if name.contains("<UDIM>") {
        name.clone()
    } else {
        let n = numbers.iter().find(|n| name.contains(&n.to_string()))?;
        name.replacen(&n.to_string(), "<UDIM>", 1)
    };
    Some(
        numbers
            .iter()
            .map(|n| path.with_file_name(pattern.replace("<UDIM>", &n.to_string())))
            .collect(),
    )
}

/// [`decode`] for a UDIM head: tile pictures laid out in its atlas. Every tile must be
/// there and square, all of one size; a missing or odd one is an error naming it.
fn decode_tiled(
    colour: Option<Source>,
    normal: Option<Source>,
    udim: &super::udim::Udim,
) -> Result<MeshTextures, Error> {
    let expand = |s: Option<Source>| match s {
        Some(Source::File(p)) => match tile_files(&p, udim) {
            Some(files) => (None, files),
            None => (Some(Source::File(p)), Vec::new()),
        },
        other => (other, Vec::new()),
    };
    let (colour, colour_tiles) = expand(colour);
    let (normal, normal_tiles) = expand(normal);
    let mut out = decode(colour, normal)?;
    for (files, colour) in [(colour_tiles, true), (normal_tiles, false)] {
        if files.is_empty() {
            continue;
        }
        let mut images = Vec::new();
        for f in &files {
            let encoding = if colour {
                Encoding::Colour
            } else {
                Encoding::Data
            };
            let image = HeadImage::load_as(f, false, encoding)?;
            let side = images
                .first()
                .map_or(image.width_px, |i: &HeadImage| i.width_px);
            if image.width_px != image.height_px || image.width_px != side {
                return Err(Error::InvalidValue {
                    what: format!("{}: size of a UDIM tile", f.display()),
                    value: format!("{}×{}", image.width_px, image.height_px),
                    expected: format!("{side}×{side}, square and as the other tiles"),
                });
            }
            images.push(image);
        }
        let side = images[0].width_px;
        let tiles: Vec<Vec<u8>> = images.into_iter().map(|i| i.rgba).collect();
        let atlas = HeadImage {
            width_px: side * udim.grid(),
            height_px: side * udim.grid(),
            rgba: udim.assemble(&tiles, side, 4, 0),
        };
        let what = if colour { "colour map" } else { "normal map" };
        out.sources.push(format!(
            "{what} {} ({} UDIM tiles)",
            files[0].display(),
            files.len()
        ));
        out.files.extend(files);
        if colour {
            out.colour = Some(std::sync::Arc::new(atlas));
        } else {
            out.normal = Some(std::sync::Arc::new(atlas));
        }
    }
    Ok(out)
}

/// The pictures embedded in the GLB `bytes` (named `name` in reports), as [`load`] reads
/// them from a file; nothing outside the bytes is read.
pub fn load_glb_bytes(bytes: &[u8], name: &Path) -> Result<MeshTextures, Error> {
    let (colour, normal) = match std::panic::catch_unwind(|| gltf_sources_in(bytes, name, None)) {
        Ok(found) => found?,
        Err(_) => {
            return Err(Error::MeshFile {
                path: name.to_owned(),
                message: "its material names an image the file does not describe fully".into(),
            });
        }
    };
    decode(colour, normal)
}

fn gltf_sources(path: &Path) -> Result<(Option<Source>, Option<Source>), Error> {
    let bytes = crate::base::limits::read_file(path, crate::base::limits::MAX_MESH_FILE_BYTES)?;
    let dir = path.parent().unwrap_or(Path::new("")).to_owned();
    gltf_sources_in(&bytes, path, Some(&dir))
}

/// The material's pictures in the glTF `bytes`; `dir` is where files beside it are read
/// (none for a GLB held in memory: a URI is then an error).
fn gltf_sources_in(
    bytes: &[u8],
    path: &Path,
    dir: Option<&Path>,
) -> Result<(Option<Source>, Option<Source>), Error> {
    let fail = |message: String| Error::MeshFile {
        path: path.to_owned(),
        message,
    };
    let gltf = super::gltf::parse(bytes).map_err(fail)?;
    // The material of the most triangles with a base colour map: the skin's.
    let mut count = vec![0usize; gltf.document.materials().len()];
    for mesh in gltf.document.meshes() {
        for prim in mesh.primitives() {
            if let (Some(i), Some(a)) = (prim.material().index(), prim.indices()) {
                count[i] += a.count() / 3;
            }
        }
    }
    let Some(material) = gltf
        .document
        .materials()
        .filter(|m| m.pbr_metallic_roughness().base_color_texture().is_some())
        .max_by_key(|m| m.index().map_or(0, |i| count[i]))
    else {
        return Ok((None, None));
    };
    let buffers = ::gltf::import_buffers(&gltf.document, dir, gltf.blob.clone())
        .map_err(|e| fail(format!("cannot read its buffers: {e}")))?;
    let source = |texture: ::gltf::Texture<'_>| -> Result<Source, Error> {
        let image = texture.source();
        match image.source() {
            ::gltf::image::Source::View { view, .. } => {
                let data = &buffers
                    .get(view.buffer().index())
                    .ok_or_else(|| fail(format!("image {} names no buffer", image.index())))?
                    .0;
                let bytes = data
                    .get(view.offset()..view.offset() + view.length())
                    .ok_or_else(|| {
                        fail(format!("image {} lies outside its buffer", image.index()))
                    })?;
                Ok(Source::Bytes(
                    bytes.to_vec(),
                    format!("{} (image {})", path.display(), image.index()),
                ))
            }
            ::gltf::image::Source::Uri { uri, .. } => {
                if uri.starts_with("data:") {
                    return Err(fail(format!(
                        "image {}: data: URIs for images are not read; embed it in a GLB or put it beside the file",
                        image.index()
                    )));
                }
                super::gltf::check_uri(uri).map_err(|why| {
                    fail(format!(
                        "image {} has the URI \"{}\", which {why}",
                        image.index(),
                        crate::base::limits::shorten(uri, 80)
                    ))
                })?;
                let dir = dir.ok_or_else(|| {
                    fail(format!("image {} is a file, not embedded", image.index()))
                })?;
                Ok(Source::File(dir.join(super::gltf::decode_uri(uri))))
            }
        }
    };
    let colour = material
        .pbr_metallic_roughness()
        .base_color_texture()
        .map(|t| source(t.texture()))
        .transpose()?;
    let normal = material
        .normal_texture()
        .map(|t| source(t.texture()))
        .transpose()?;
    Ok((colour, normal))
}

/// The OBJ's `mtllib`, and in it the first `map_Kd` (colour) and `norm` (tangent normal
/// map) — files of the OBJ's folder.
fn obj_sources(path: &Path) -> Result<(Option<Source>, Option<Source>), Error> {
    let bytes = crate::base::limits::read_file(path, crate::base::limits::MAX_MESH_FILE_BYTES)?;
    let text = String::from_utf8_lossy(&bytes);
    let dir = path.parent().unwrap_or(Path::new("")).to_owned();
    let Some(mtl) = text
        .lines()
        .find_map(|l| l.trim().strip_prefix("mtllib ").map(str::trim))
    else {
        return Ok((None, None));
    };
    let inside = |name: &str, what: &str, from: &Path| -> Result<PathBuf, Error> {
        super::gltf::check_uri(name).map_err(|why| Error::MeshFile {
            path: from.to_owned(),
            message: format!(
                "{what} \"{}\" {why}",
                crate::base::limits::shorten(name, 80)
            ),
        })?;
        Ok(dir.join(name))
    };
    let mtl_path = inside(mtl, "mtllib", path)?;
    // A missing material library is no error for the mesh: OBJ readers skip it.
    let Ok(mtl_bytes) =
        crate::base::limits::read_file(&mtl_path, crate::base::limits::MAX_TEXT_FILE_BYTES)
    else {
        return Ok((None, None));
    };
    let mtl_text = String::from_utf8_lossy(&mtl_bytes);
    // The file name is the statement's last word (options like `-bm 1` come before).
    let map = |key: &str| {
        mtl_text.lines().find_map(|l| {
            let mut words = l.split_whitespace();
            (words.next() == Some(key)).then(|| words.last().map(str::to_owned))?
        })
    };
    let colour = map("map_Kd")
        .map(|n| inside(&n, "map_Kd", &mtl_path).map(Source::File))
        .transpose()?;
    let normal = map("norm")
        .map(|n| inside(&n, "norm", &mtl_path).map(Source::File))
        .transpose()?;
    Ok((colour, normal))
}
