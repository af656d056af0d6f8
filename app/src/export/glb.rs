//! The aged head as binary glTF: the mesh with its `age` morph target, its materials and
//! maps, and the hair beside it.

use std::path::PathBuf;

use agesim_core::base::cancel::CancelToken;
use agesim_core::head::mesh::udim::Udim;
use agesim_core::layers::hair::GrayingRamp;
use agesim_core::output::export::OutputSet;
use agesim_core::scene::{BakeRequest, Scene};
use agesim_core::{HeightMap, output::compose, output::export as out};
use anyhow::Context as _;
use glam::Vec3;

use super::{GlbOut, Progress, atlas_size, crease_maps};
use crate::view;
use agesim_core::head::mesh::gltf::{GlbExtraMesh, GlbMaterial, GlbMorph, write_glb_with_extras};
use agesim_core::layers::hair::strand::{HairLook, HairMesh, StrandStyle};

/// The bake of the GLB's head at `atlas_px` (`size_px` per UDIM tile) and age `t`: the
/// large wrinkles over the atlas, the micro-relief and fine-wrinkle tiles that repeat over
/// it, the shape's relief.
pub fn glb_bake_request(atlas_px: u32, size_px: u32, t: f32) -> BakeRequest {
    BakeRequest {
        large_size_px: atlas_px,
        micro_size_px: 1024.min(size_px.max(64)),
        t,
        // The tiles repeat over the head: they must wrap.
        tileable: true,
        fine: true,
        hair: false,
        packed: false,
        one_off: true,
        micro_normals: false,
        shape_relief: true,
    }
}

/// Stages the GLB and its wrinkle height map(s); returns the files.
#[allow(clippy::too_many_arguments)]
pub(super) fn export_glb(
    base: &Scene,
    t: f32,
    years: f32,
    glb: &GlbOut,
    set: &OutputSet,
    progress: Progress<'_>,
    cancel: &CancelToken,
) -> anyhow::Result<Vec<PathBuf>> {
    progress(0.0, "loading the head");
    let mut scene = base.fork();
    let udim = scene.mesh().udim().cloned();
    let atlas_px = atlas_size(udim.as_ref(), glb.size_px, "GLB texture size")?;
    progress(0.1, "baking the head's maps");
    let request = glb_bake_request(atlas_px, glb.size_px, t);
    scene.bake(&request, cancel)?;
    progress(0.5, "composing the normal map");
    let normals = head_normal_map(&scene, t, atlas_px, cancel)?;
    cancel.check()?;
    let project = scene.project();
    let head = view::HeadScale::of(&scene);
    let mpu = head.metres_per_unit;
    let params = view::frame_params(project, head, t, view::camera(project, mpu, Vec3::ZERO));
    let depth = scene.large_depth();
    let height = match scene.large() {
        Some(l) => l.scaled(depth)?,
        None => HeightMap::zeros(atlas_px, atlas_px)?,
    };
    let range = scene.large().map(|_| height.min_max());
    // The creases' cavity occlusion, as the view darkens them, and their rougher floors
    // on the skin's roughness at this age (docs/models.md §10), as glTF packs them.
    let orm = scene
        .large()
        .is_some_and(|l| l.height.width_px() == atlas_px)
        .then(|| crease_maps(&scene, t, atlas_px));
    // The aged base colour (docs/models.md "Skin colour"): the head's own colour map, or
    // the skin colour, with its spots, uneven tone and paling at this age, at the colour
    // map's own size (`Scene::colour_px`; 1024² even for smaller GLB textures).
    let colour_px = scene.colour_px(atlas_px.max(1024));
    scene.bake_colour(colour_px, t, cancel)?;
    let aged = scene.exported_colour();
    let base_colour = [1.0; 4];
    // One material per UDIM tile (one for a single-tile head), each with its tile's maps.
    let tiles = udim.as_ref().map_or(vec![0], |u| u.numbers());
    let multi = tiles.len() > 1;
    let height_paths = Udim::paths(udim.as_ref(), &glb.height_path());
    let mut materials = Vec::new();
    for (k, &number) in tiles.iter().enumerate() {
        progress(
            0.7 + 0.2 * k as f32 / tiles.len() as f32,
            "encoding the textures",
        );
        // One atlas picture (`w`×`h`) as this tile's PNG: its cell of a multi-tile
        // head's atlas, or the whole picture.
        let tile_png = |texels: &[u8],
                        (w, h): (u32, u32),
                        pixels: out::PngPixels,
                        channels: usize,
                        what: &str| {
            let (texels, w, h) = match &udim {
                Some(u) if multi => {
                    let side = w / u.grid();
                    (u.crop(k, texels, w, channels), side, side)
                }
                _ => (texels.to_vec(), w, h),
            };
            let mut png = Vec::new();
            out::encode_png(&mut png, w, h, pixels, &texels)
                .with_context(|| format!("encoding the {what}"))?;
            anyhow::Ok(png)
        };
        let atlas = (atlas_px, atlas_px);
        let normal_png = tile_png(&normals, atlas, out::PngPixels::Rgb8, 3, "normal map")?;
        let orm_png = orm
            .as_ref()
            .map(|orm| tile_png(orm, atlas, out::PngPixels::Rgb8, 3, "roughness map"))
            .transpose()?;
        let base_colour_png = aged
            .as_ref()
            .map(|c| {
                let size = (c.width_px, c.height_px);
                tile_png(&c.rgba, size, out::PngPixels::Rgba8, 4, "base colour map")
            })
            .transpose()?;
        let height_name = height_paths[k]
            .file_name()
            .map(|n| n.to_string_lossy().into_owned())
            .unwrap_or_default();
        materials.push(GlbMaterial {
            name: if multi {
                format!("agesim skin, {years:.0} years, UDIM {number}")
            } else {
                format!("agesim skin, {years:.0} years")
            },
            base_colour,
            base_colour_png,
            // The skin's roughness at this age (old skin is drier: docs/models.md "Skin
            // colour", "Sheen"): in the texture when there is one, which the factor
            // multiplies.
            roughness: if orm_png.is_some() {
                1.0
            } else {
                params.skin.roughness
            },
            metallic: if orm_png.is_some() { 1.0 } else { 0.0 },
            normal_png: Some(normal_png),
            orm_png,
            extras: serde_json::json!({
                "agesim_version": env!("CARGO_PKG_VERSION"),
                "age_years": years,
                "age_t": t,
                "udim_tile": multi.then_some(number),
                "height_map": height_name,
                "height_range": range.map(|(lo, hi)| [lo, hi]),
                "height_meaning": "large-wrinkle height = lo + (hi - lo) * p / 65535 for a 16-bit value p, in the project's height units (the deepest: large.depth, past 80 years times the old-age depth gain)",
            }),
        });
    }
    cancel.check()?;
    // glTF is in metres, +Y up, +Z forward: the scene's mesh is turned already; its
    // units are made metres here (a head in centimetres or the scan's 0.052 m).
    let mesh = match mpu {
        1.0 => scene.mesh().clone(),
        m => std::sync::Arc::new(scene.mesh().scaled(m)),
    };
    // Age changes the shape (docs/models.md §13), as two morph targets in metres like
    // the mesh: `age`, every region's full move, and `old_age`, what the old age adds to
    // it (75 to 90); their weights the chosen age's.
    let morphs: Vec<GlbMorph> = scene.shape_field().map_or(Vec::new(), |field| {
        let head = scene.mesh();
        let whole = field.whole();
        let oldest = field.full();
        let (n_whole, n_oldest) = (field.normals(head, &whole), field.normals(head, &oldest));
        // Each state's tangent: the original made perpendicular to that state's normal.
        let tangents = |normals: &[Vec3]| -> Vec<Vec3> {
            head.tangents()
                .iter()
                .zip(normals)
                .map(|(t, n)| {
                    let t3 = t.truncate();
                    (t3 - *n * n.dot(t3)).normalize_or(t3)
                })
                .collect()
        };
        let rest_t: Vec<Vec3> = head.tangents().iter().map(|t| t.truncate()).collect();
        let (t_whole, t_oldest) = (tangents(&n_whole), tangents(&n_oldest));
        let minus = |a: &[Vec3], b: &[Vec3]| a.iter().zip(b).map(|(a, b)| *a - *b).collect();
        let [w_age, w_old] = field.morph_weights(years);
        vec![
            GlbMorph {
                name: "age".into(),
                position: whole.iter().map(|d| *d * mpu).collect(),
                normal: minus(&n_whole, head.normals()),
                tangent: minus(&t_whole, &rest_t),
                weight: w_age,
            },
            GlbMorph {
                name: "old_age".into(),
                position: field.old_age().iter().map(|d| *d * mpu).collect(),
                normal: minus(&n_oldest, &n_whole),
                tangent: minus(&t_oldest, &t_whole),
                weight: w_old,
            },
        ]
    });
    progress(0.85, "making the hair");
    let hair: Vec<GlbExtraMesh> = match glb.hair.stride() {
        Some(stride) => hair_mesh(&mut scene, &request, years, stride, cancel)?
            .into_iter()
            .collect(),
        None => Vec::new(),
    };
    cancel.check()?;
    let bytes = write_glb_with_extras(&mesh, &materials, &morphs, &hair);
    progress(0.9, "writing the GLB");
    set.stage(&glb.path, |w| std::io::Write::write_all(w, &bytes))?;
    // The wrinkle heights beside it, tile by tile on one range.
    let settings = scene.normal_settings();
    out::stage_tiled_maps(
        set,
        out::MapPaths {
            height_png: Some(&glb.height_path()),
            ..Default::default()
        },
        &height,
        &settings,
        Default::default(),
        udim.as_ref(),
    )?;
    let mut files = vec![glb.path.clone()];
    files.extend(height_paths);
    Ok(files)
}

/// The head's tangent-space normal map of `scene` at age `t`, `size_px`² over the head's
/// UV square: the layers composed as the renderer's skin pass does
/// ([`agesim_core::output::compose`]), with the same relief depth, tiles and fine blend as the
/// 3D view ([`view::frame_params`]).
pub fn head_normal_map(
    scene: &Scene,
    t: f32,
    size_px: u32,
    cancel: &CancelToken,
) -> anyhow::Result<Vec<u8>> {
    let project = scene.project();
    let scale = scene
        .surface_scale()
        .context("the mesh's UVs are degenerate: no normal map can be laid on it")?;
    let head = view::HeadScale::of(scene);
    let mpu = head.metres_per_unit;
    let skin = view::frame_params(project, head, t, view::camera(project, mpu, Vec3::ZERO)).skin;
    let tile = |heights, placement: agesim_render::TilePlacement| compose::RepeatedTile {
        heights,
        repeats: scale.repeats(mpu, placement.size_m.max(1e-6)),
        strength: placement.strength,
    };
    let layers = compose::Layers {
        large: scene.large().map(|l| &l.height),
        disp_scale: skin.disp_scale,
        fine: scene.fine().map(|f| tile(f.as_ref(), skin.fine_tile)),
        fine_blend: skin.fine_blend,
        micro: scene
            .micro()
            .filter(|_| skin.micro_relief)
            .map(|m| tile(&m.height, skin.micro_tile)),
        micro_weight: scene.micro_weight().map(|m| m.as_ref()),
        head_normal: scene
            .normal_map()
            .map(|m| (m.as_ref(), skin.head_normal_green_down)),
    };
    Ok(compose::normal_map(&layers, size_px, cancel)?)
}

/// A hair's width at its root, metres: a scalp hair's diameter is 50–100 µm (Robbins,
/// *Chemical and Physical Behavior of Human Hair*), a ribbon of 80 µm.
const HAIR_WIDTH_M: f32 = 80e-6;

/// Segments of each exported strand (the view's full-quality ribbon).
const HAIR_SEGMENTS: u32 = 4;

/// The hair of `scene` at the age of `request` as the GLB's `hair` mesh, in metres
/// (docs/models.md §9 "The hair in the GLB"): the scalp hair present (one in `stride`) and
/// the brows and lashes, each strand a ribbon along the curve the view draws, coloured as
/// the view colours it at that age; `None` without hair. Placed after the maps and the
/// base colour were made (the same with or without the hair in the file).
fn hair_mesh(
    scene: &mut Scene,
    request: &BakeRequest,
    years: f32,
    stride: usize,
    cancel: &CancelToken,
) -> anyhow::Result<Option<GlbExtraMesh>> {
    if !scene.project().hair.enabled {
        return Ok(None);
    }
    let t = request.t;
    scene.bake(
        &BakeRequest {
            hair: true,
            ..*request
        },
        cancel,
    )?;
    scene.bake_brows(t);
    let head = view::HeadScale::of(scene);
    let mpu = head.metres_per_unit;
    let project = scene.project();
    let hair = view::frame_params(project, head, t, view::camera(project, mpu, Vec3::ZERO)).hair;
    let look = HairLook {
        style: StrandStyle {
            length: hair.length,
            droop: hair.droop,
            curl: hair.curl,
        },
        base: hair.base_colour,
        gray: hair.gray_colour,
        brow: hair.brow_colour,
        ramp: match hair.ramp {
            agesim_render::GrayingRampParam::Linear => GrayingRamp::Linear,
            agesim_render::GrayingRampParam::Smoothstep => GrayingRamp::Smoothstep,
        },
        width: HAIR_WIDTH_M / mpu.max(1e-9),
    };
    let brows = scene.aged_brows().map_or(&[][..], |b| b.as_slice());
    let Some(hairs) = scene.hair() else {
        return Ok(None);
    };
    let mesh = HairMesh::new(hairs, brows, &look, t, stride, HAIR_SEGMENTS);
    if mesh.indices.is_empty() {
        return Ok(None);
    }
    Ok(Some(GlbExtraMesh {
        name: agesim_core::head::mesh::gltf::AGESIM_HAIR_MESH.into(),
        positions: mesh.positions.iter().map(|p| *p * mpu).collect(),
        normals: mesh.normals,
        colours: mesh.colours,
        indices: mesh.indices,
        material_name: format!("agesim hair, {years:.0} years"),
        roughness: 0.45,
    }))
}
