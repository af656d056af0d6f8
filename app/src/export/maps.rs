//! The maps of an export and of `agesim bake`: heights, normals, the aged base colour, the
//! skin's roughness and occlusion, over the head's layout and cut per UDIM tile.

use std::path::PathBuf;

use agesim_core::base::cancel::CancelToken;
use agesim_core::head::mesh::udim::Udim;
use agesim_core::output::export::OutputSet;
use agesim_core::scene::{BakeRequest, Scene};
use agesim_core::{HeightMap, output::compose, output::export as out};
use anyhow::bail;
use glam::Vec3;

use super::{MapPaths, MapsOut, Progress, atlas_size};
use crate::view;

/// Stages the maps; returns the files (one per UDIM tile and map on a multi-tile head).
pub(super) fn export_maps(
    base: &Scene,
    t: f32,
    maps: &MapsOut,
    set: &OutputSet,
    progress: Progress<'_>,
    cancel: &CancelToken,
) -> anyhow::Result<Vec<PathBuf>> {
    let mut p = base.project().clone();
    if let Some(c) = maps.convention {
        p.normal.convention = c;
    }
    progress(0.0, "loading the inputs");
    let mut scene = base.fork();
    scene.set_project(p)?;
    progress(0.1, "baking the maps");
    let wanted = Wanted {
        colour: maps.base_colour_png.is_some(),
        crease: maps.roughness_png.is_some() || maps.ao_png.is_some(),
    };
    let baked = bake_maps(
        &mut scene,
        t,
        maps.size_px,
        maps.tileable,
        wanted,
        "map size",
        cancel,
    )?;
    cancel.check()?;
    progress(0.6, "writing the maps");
    let (_, files) = stage_maps(set, maps.paths(), &baked, maps.exr_compression)?;
    Ok(files)
}

/// What [`bake_maps`] makes besides the heights: the aged base colour, the creases'
/// occlusion and roughness.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct Wanted {
    pub colour: bool,
    pub crease: bool,
}

/// The maps of a bake or an export at one age: the heights over the head's layout (a
/// multi-tile head's UDIM atlas), its normal settings and what each step took.
pub struct BakedMaps {
    pub height: HeightMap,
    pub normal: agesim_core::maps::normal_map::NormalSettings,
    pub udim: Option<Udim>,
    /// The aged base colour, when asked for.
    pub colour: Option<std::sync::Arc<agesim_core::maps::mask::HeadImage>>,
    /// The skin's occlusion, roughness and metallic over the heights' texels
    /// ([`crease_maps`]), when asked for; empty otherwise.
    pub orm: Vec<u8>,
    /// Milliseconds: the bake, the aged colour (the two side by side), taking the height
    /// map out of the scene.
    pub bake_ms: f64,
    pub colour_ms: f64,
    pub take_ms: f64,
}

/// Bakes `scene`'s maps at age `t`, `size_px` per UDIM tile (`what` names that setting in
/// errors), and with `colour` the aged base colour at the scene's size for them
/// ([`Scene::colour_px`]; in [`BakedMaps::colour`]): the one path of `agesim bake` and of
/// the export's maps.
pub fn bake_maps(
    scene: &mut Scene,
    t: f32,
    size_px: u32,
    tileable: bool,
    wanted: Wanted,
    what: &str,
    cancel: &CancelToken,
) -> anyhow::Result<BakedMaps> {
    let colour = wanted.colour;
    // A UDIM head is baked over its atlas, `size_px` per tile, and cut into tiles.
    let udim = scene.mesh().udim().cloned();
    let atlas_px = atlas_size(udim.as_ref(), size_px, what)?;
    let ms = |t: std::time::Instant| t.elapsed().as_secs_f64() * 1e3;
    // The aged colour needs nothing the maps' bake makes (no hair: its transition is the
    // scene's as it is): it is baked beside them, on a fork of the scene sharing its
    // inputs and the person's colours measured once.
    let mut colour_scene = None;
    if colour {
        scene.own_colours(cancel)?;
        colour_scene = Some(scene.fork());
    }
    let colour_px = scene.colour_px(atlas_px);
    let ((bake, bake_ms), (aged, colour_ms)) = rayon::join(
        || {
            let start = std::time::Instant::now();
            let r = scene.bake(&BakeRequest::maps(atlas_px, t, tileable), cancel);
            (r, ms(start))
        },
        || {
            let start = std::time::Instant::now();
            let aged = colour_scene.as_mut().map(|s| {
                s.bake_colour(colour_px, t, cancel)?;
                Ok::<_, agesim_core::Error>(s.exported_colour())
            });
            (aged.transpose(), ms(start))
        },
    );
    bake?;
    let colour = aged?.flatten();
    let start = std::time::Instant::now();
    let orm = if wanted.crease {
        crease_maps(scene, t, atlas_px)
    } else {
        Vec::new()
    };
    let height = scene.take_height()?;
    let take_ms = ms(start);
    Ok(BakedMaps {
        height,
        normal: scene.normal_settings(),
        udim,
        colour,
        orm,
        bake_ms,
        colour_ms,
        take_ms,
    })
}

/// Stages `maps` at `paths` in `set` (per UDIM tile on a multi-tile head); returns what the
/// staging measured and the files.
pub fn stage_maps(
    set: &OutputSet,
    paths: MapPaths<'_>,
    maps: &BakedMaps,
    compression: out::ExrCompression,
) -> anyhow::Result<(out::MapsStaged, Vec<PathBuf>)> {
    let udim = maps.udim.as_ref();
    let mut files: Vec<PathBuf> = [paths.height_png, paths.height_exr, paths.normal_png]
        .into_iter()
        .flatten()
        .flat_map(|p| Udim::paths(udim, p))
        .collect();
    let staged = out::stage_tiled_maps(
        set,
        out::MapPaths {
            height_png: paths.height_png,
            height_exr: paths.height_exr,
            normal_png: paths.normal_png,
        },
        &maps.height,
        &maps.normal,
        compression,
        udim,
    )?;
    if let Some(path) = paths.base_colour_png {
        let Some(colour) = &maps.colour else {
            bail!("{}: the base colour was not baked", path.display());
        };
        out::stage_tiled_colour(set, path, colour, udim)?;
        files.extend(Udim::paths(udim, path));
    }
    let side = maps.height.width_px();
    for (path, channel) in [(paths.ao_png, 0), (paths.roughness_png, 1)] {
        let Some(path) = path else { continue };
        if maps.orm.len() != (side as usize).pow(2) * 3 {
            bail!(
                "{}: the roughness and occlusion were made at another size than the heights ({side}²)",
                path.display()
            );
        }
        let grey: Vec<u8> = maps.orm.chunks_exact(3).map(|p| p[channel]).collect();
        files.extend(out::stage_tiled_png(
            set,
            path,
            &grey,
            side,
            out::PngPixels::Grey8,
            udim,
        )?);
    }
    Ok((staged, files))
}

/// The skin's occlusion, roughness and metallic at age `t` over `side_px`² texels of the
/// head's layout, packed as glTF's ORM texture (8-bit RGB: `compose::orm_map`): the
/// creases' cavity occlusion and their rougher floors from the large wrinkles, drawn as
/// deep as the view draws them, on the skin's roughness at that age (old skin is drier);
/// open skin everywhere when no large-wrinkle map of that size was baked.
pub fn crease_maps(scene: &Scene, t: f32, side_px: u32) -> Vec<u8> {
    let project = scene.project();
    let head = view::HeadScale::of(scene);
    let camera = view::camera(project, head.metres_per_unit, Vec3::ZERO);
    let skin = view::frame_params(project, head, t, camera).skin;
    match scene.large().filter(|l| l.height.width_px() == side_px) {
        Some(l) => compose::orm_map(&l.height, skin.disp_scale, skin.roughness),
        None => {
            let r = (skin.roughness.clamp(0.0, 1.0) * 255.0).round() as u8;
            [255, r, 0].repeat((side_px as usize).pow(2))
        }
    }
}
