//! Exports at an age, shared by `agesim export` and the editor's Export window: the maps
//! (height as 16-bit PNG and 32-bit EXR, normal PNG), renders (one image, an age sequence,
//! a young | old comparison) and the aged head as GLB.
//!
//! Everything one request writes is one output set (`agesim_core::output::export::OutputSet`):
//! each file goes to a temporary first, and only when every file is written are they all
//! renamed into place. An error or a cancel leaves the old files whole and no temporary.

use std::path::{Path, PathBuf};

use agesim_core::base::cancel::CancelToken;
use agesim_core::head::mesh::gltf::{GlbMaterial, GlbMorph, write_glb_with_morph};
use agesim_core::head::mesh::udim::Udim;
use agesim_core::maps::normal_map::Convention;
use agesim_core::output::export::OutputSet;
use agesim_core::project::Project;
use agesim_core::scene::{BakeRequest, Scene, WrinkleSource};
use agesim_core::{HeightMap, maps::heightmap, output::compose, output::export as out};
use anyhow::{Context as _, bail};
use glam::Vec3;

use crate::view;

/// The maps of `agesim bake` (the large wrinkles on the head's UV plus the micro-relief
/// over the whole square, the aged base colour, the skin's roughness and occlusion), at
/// one size.
#[derive(Clone, Debug, Default)]
pub struct MapsOut {
    pub size_px: u32,
    pub height_png: Option<PathBuf>,
    pub height_exr: Option<PathBuf>,
    pub normal_png: Option<PathBuf>,
    /// The aged base colour, 8-bit RGB at the head's colour map's size (1024–2048).
    pub base_colour_png: Option<PathBuf>,
    /// The skin's roughness at the age, rougher in the creases (8-bit grey).
    pub roughness_png: Option<PathBuf>,
    /// The creases' cavity occlusion (8-bit grey, 255 = open skin).
    pub ao_png: Option<PathBuf>,
    /// The normal map's green channel; `None`: the project's `normal.convention`.
    pub convention: Option<Convention>,
    /// Bake the micro-relief periodic, so the maps tile (the skin patch).
    pub tileable: bool,
    /// The height EXR's (lossless) compression.
    pub exr_compression: agesim_core::output::export::ExrCompression,
}

impl MapsOut {
    fn any(&self) -> bool {
        !self.files().is_empty()
    }

    /// The files asked for, in order.
    fn files(&self) -> Vec<&PathBuf> {
        [
            &self.height_png,
            &self.height_exr,
            &self.normal_png,
            &self.base_colour_png,
            &self.roughness_png,
            &self.ao_png,
        ]
        .into_iter()
        .flatten()
        .collect()
    }

    /// Where the maps go, for [`stage_maps`].
    pub fn paths(&self) -> MapPaths<'_> {
        MapPaths {
            height_png: self.height_png.as_deref(),
            height_exr: self.height_exr.as_deref(),
            normal_png: self.normal_png.as_deref(),
            base_colour_png: self.base_colour_png.as_deref(),
            roughness_png: self.roughness_png.as_deref(),
            ao_png: self.ao_png.as_deref(),
        }
    }
}

/// Where [`stage_maps`] writes each map (`None`: not written).
#[derive(Clone, Copy, Debug, Default)]
pub struct MapPaths<'a> {
    pub height_png: Option<&'a Path>,
    pub height_exr: Option<&'a Path>,
    pub normal_png: Option<&'a Path>,
    pub base_colour_png: Option<&'a Path>,
    pub roughness_png: Option<&'a Path>,
    pub ao_png: Option<&'a Path>,
}

/// The aged head as a binary glTF: mesh with tangents, a material whose `normalTexture`
/// is the large-wrinkle, fine-wrinkle and micro-relief normal map at the age, and a base
/// colour for the age. glTF has no displacement, so the large-wrinkle height map is
/// written beside it (`NAME_wrinkle_height.png`, 16-bit).
#[derive(Clone, Debug)]
pub struct GlbOut {
    pub path: PathBuf,
    /// Side of the normal and height maps, px.
    pub size_px: u32,
}

impl GlbOut {
    /// `head.glb` → `head_wrinkle_height.png`.
    pub fn height_path(&self) -> PathBuf {
        sibling(&self.path, "_wrinkle_height", "png")
    }
}

/// Renders with the wgpu renderer, in the project's camera and light.
#[derive(Clone, Debug, Default)]
pub struct RendersOut {
    /// Image size, px.
    pub size: (u32, u32),
    /// One image at the request's age.
    pub image: Option<PathBuf>,
    /// One image per age (years): `FILE_0000.png`, `FILE_0001.png`, ….
    pub sequence: Option<(PathBuf, Vec<f32>)>,
    /// Two ages (years) side by side, each labelled.
    pub compare: Option<(PathBuf, [f32; 2])>,
}

impl RendersOut {
    fn any(&self) -> bool {
        self.image.is_some() || self.sequence.is_some() || self.compare.is_some()
    }

    /// The images, in order.
    fn outputs(&self) -> Vec<PathBuf> {
        let mut files: Vec<PathBuf> = self.image.iter().cloned().collect();
        if let Some((path, years)) = &self.sequence {
            files.extend((0..years.len()).map(|i| view::numbered(path, i)));
        }
        files.extend(self.compare.iter().map(|(p, _)| p.clone()));
        files
    }
}

/// One export: what to write, at which age.
#[derive(Clone, Debug, Default)]
pub struct ExportRequest {
    /// The age, years (mapped to t through the project's `age` section).
    pub years: f32,
    pub maps: MapsOut,
    pub glb: Option<GlbOut>,
    pub renders: RendersOut,
}

impl ExportRequest {
    /// Every file the request names, in order (a multi-tile head's maps are written one
    /// per UDIM tile: `height.1001.png`, …; [`run`] returns those).
    pub fn outputs(&self) -> Vec<PathBuf> {
        let mut files: Vec<PathBuf> = self.maps.files().into_iter().cloned().collect();
        if let Some(g) = &self.glb {
            files.push(g.path.clone());
            files.push(g.height_path());
        }
        files.extend(self.renders.outputs());
        files
    }
}

/// Reports progress: a fraction in [0, 1] and what is being done.
pub type Progress<'a> = &'a (dyn Fn(f32, &str) + Sync);

/// Bytes a map bake of `size_px`² needs at its peak: the f32 large and total heights, the
/// u16 copy and its PNG byte buffer, and the RGB normals.
pub fn peak_bytes(size_px: u32) -> u64 {
    (size_px as u64).pow(2) * (4 + 4 + 2 + 2 + 3)
}

/// MemAvailable from /proc/meminfo, when the platform has it.
pub fn available_memory_bytes() -> Option<u64> {
    let text = std::fs::read_to_string("/proc/meminfo").ok()?;
    let line = text.lines().find(|l| l.starts_with("MemAvailable:"))?;
    let kib: u64 = line.split_whitespace().nth(1)?.parse().ok()?;
    Some(kib * 1024)
}

/// Refuses a map size outside the engine's range, or one this machine's free memory
/// cannot hold, before any work starts; `what` names the setting in the message.
pub fn check_map_size(size_px: u32, what: &str) -> anyhow::Result<()> {
    heightmap::check_size(size_px, size_px).with_context(|| format!("{what} {size_px}"))?;
    if let Some(available) = available_memory_bytes() {
        let needed = peak_bytes(size_px);
        if needed > available {
            bail!(
                "{what} {size_px}: a {size_px}×{size_px} map needs about {} MiB but only {} MiB are available; choose a smaller size",
                needed >> 20,
                available >> 20
            );
        }
    }
    Ok(())
}

/// Runs `request` for `project` (with the editor's edited wrinkle files when given).
/// Returns the files written. On an error or a cancel nothing at the outputs changed.
pub fn run(
    project: &Project,
    wrinkles: Option<&[WrinkleSource]>,
    request: &ExportRequest,
    progress: Progress<'_>,
    cancel: &CancelToken,
) -> anyhow::Result<Vec<PathBuf>> {
    let outputs = request.outputs();
    if outputs.is_empty() {
        bail!("nothing to export: choose at least one map, the GLB or a render");
    }
    if !(0.0..=150.0).contains(&request.years) {
        bail!("age {} years: expected 0..=150", request.years);
    }
    for (i, a) in outputs.iter().enumerate() {
        if outputs[..i].contains(a) {
            bail!("{} is chosen twice as an output", a.display());
        }
    }
    if request.maps.any() {
        check_map_size(request.maps.size_px, "map size")?;
    }
    if let Some(g) = &request.glb {
        check_map_size(g.size_px, "GLB texture size")?;
        if g.path.extension().and_then(|e| e.to_str()) != Some("glb") {
            bail!(
                "{}: the aged head is written as binary glTF; name the file *.glb",
                g.path.display()
            );
        }
    }
    let r = &request.renders;
    if r.any() {
        let (w, h) = r.size;
        if !(1..=8192).contains(&w) || !(1..=8192).contains(&h) {
            bail!("render size {w}×{h}: expected 1..=8192 on each side");
        }
    }
    for path in &outputs {
        if let Some(dir) = path.parent().filter(|d| !d.as_os_str().is_empty()) {
            std::fs::create_dir_all(dir)
                .with_context(|| format!("cannot create the folder {}", dir.display()))?;
        }
    }
    let t = project.age.mapping().t(request.years);
    let set = OutputSet::new();
    // The files written: the outputs, a multi-tile (UDIM) head's maps one per tile.
    let mut written = Vec::new();
    // Shares of the progress bar per part, by rough cost.
    let parts = [
        request.maps.any() as u8 as f32,
        request.glb.is_some() as u8 as f32,
        r.any() as u8 as f32 * 1.5,
    ];
    let total: f32 = parts.iter().sum();
    let mut done = 0.0;
    let mut step = |k: usize| {
        let start = done / total;
        done += parts[k];
        (start, parts[k] / total)
    };
    // The head is loaded, fitted and its shape made once: each part bakes on a fork of
    // this scene (the inputs and the shape field, with its sky, shared; a 1.13M-triangle
    // head's shape is seconds).
    let mut base = scene(project.clone(), wrinkles)?;
    if request.glb.is_some() || r.any() {
        base.shape_field();
    }
    if request.maps.any() {
        let (start, share) = step(0);
        let p = |f: f32, what: &str| progress(start + share * f, what);
        written.extend(export_maps(&base, t, &request.maps, &set, &p, cancel)?);
    }
    if let Some(glb) = &request.glb {
        let (start, share) = step(1);
        let p = |f: f32, what: &str| progress(start + share * f, what);
        written.extend(export_glb(&base, t, request.years, glb, &set, &p, cancel)?);
    }
    if r.any() {
        let (start, share) = step(2);
        let p = |f: f32, what: &str| progress(start + share * f, what);
        export_renders(&base, t, r, &set, &p, cancel)?;
        written.extend(r.outputs());
    }
    cancel.check()?;
    progress(1.0, "putting the files in place");
    set.commit()?;
    Ok(written)
}

/// A scene of `project` with the edited wrinkle files.
fn scene(project: Project, wrinkles: Option<&[WrinkleSource]>) -> anyhow::Result<Scene> {
    let mut scene = Scene::new(project)?;
    if let Some(w) = wrinkles {
        scene.set_wrinkles(w.to_vec());
    }
    Ok(scene)
}

/// Stages the maps; returns the files (one per UDIM tile and map on a multi-tile head).
fn export_maps(
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
    let baked = bake_maps(
        &mut scene,
        t,
        maps.size_px,
        maps.tileable,
        maps.base_colour_png.is_some(),
        "map size",
        cancel,
    )?;
    cancel.check()?;
    progress(0.6, "writing the maps");
    let (_, files) = stage_maps(set, maps.paths(), &baked, maps.exr_compression)?;
    Ok(files)
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
    /// ([`crease_maps`]).
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
    colour: bool,
    what: &str,
    cancel: &CancelToken,
) -> anyhow::Result<BakedMaps> {
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
                Ok::<_, agesim_core::Error>(s.aged_colour().cloned())
            });
            (aged.transpose(), ms(start))
        },
    );
    bake?;
    let colour = aged?.flatten();
    let start = std::time::Instant::now();
    let orm = crease_maps(scene, t, atlas_px);
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

/// The side of a bake over `udim`'s atlas with `tile_px` per tile (`tile_px` for a
/// single-tile head), refused when too large (`what` names the setting).
pub fn atlas_size(udim: Option<&Udim>, tile_px: u32, what: &str) -> anyhow::Result<u32> {
    let grid = udim.map_or(1, Udim::grid);
    let atlas_px = tile_px.saturating_mul(grid);
    if grid > 1 {
        check_map_size(atlas_px, what).with_context(|| {
            format!(
                "{what} {tile_px} per tile: the head's {} UDIM tiles are baked side by side, {grid} × {grid}",
                udim.map_or(1, |u| u.tiles().len())
            )
        })?;
    }
    Ok(atlas_px)
}

/// Stages the GLB and its wrinkle height map(s); returns the files.
#[allow(clippy::too_many_arguments)]
fn export_glb(
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
    scene.bake(&glb_bake_request(atlas_px, glb.size_px, t), cancel)?;
    progress(0.5, "composing the normal map");
    let normals = head_normal_map(&scene, t, atlas_px, cancel)?;
    cancel.check()?;
    let project = scene.project();
    let head = view::HeadScale::of(&scene);
    let mpu = head.metres_per_unit;
    let params = view::frame_params(project, head, t, view::camera(project, mpu, Vec3::ZERO));
    let depth = project.large.depth;
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
    let aged = scene.aged_colour().cloned();
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
                "height_meaning": "large-wrinkle height = lo + (hi - lo) * p / 65535 for a 16-bit value p, in the project's height units (large.depth = deepest)",
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
    // Age changes the shape (docs/models.md §13): the full old-age displacement as the
    // `age` morph target, its weight the chosen age's, in metres like the mesh.
    let morph = scene.shape_field().map(|field| {
        let full = field.full();
        let head = scene.mesh();
        let normals = field.normals(head, &full);
        let tangent = head
            .tangents()
            .iter()
            .zip(&normals)
            .map(|(t, n)| {
                let t3 = t.truncate();
                (t3 - *n * n.dot(t3)).normalize_or(t3) - t3
            })
            .collect();
        GlbMorph {
            name: "age".into(),
            position: full.iter().map(|d| *d * mpu).collect(),
            normal: normals
                .iter()
                .zip(head.normals())
                .map(|(n, n0)| *n - *n0)
                .collect(),
            tangent,
            weight: field.weight_at(years),
        }
    });
    let bytes = write_glb_with_morph(&mesh, &materials, morph.as_ref());
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
        head_normal: scene
            .normal_map()
            .map(|m| (m.as_ref(), skin.head_normal_green_down)),
    };
    Ok(compose::normal_map(&layers, size_px, cancel)?)
}

fn export_renders(
    base: &Scene,
    t: f32,
    r: &RendersOut,
    set: &OutputSet,
    progress: Progress<'_>,
    cancel: &CancelToken,
) -> anyhow::Result<()> {
    use agesim_render::{Gpu, Renderer};
    progress(0.0, "starting the renderer");
    let scene = base.fork();
    let project = base.project();
    let centre = scene.mesh().bounds().centre();
    let mut shown = view::HeadlessView::new(scene, 1024, project.hair.enabled);
    let gpu = Gpu::new()?;
    let mut renderer = Renderer::new(&gpu.device, &gpu.queue, agesim_render::COLOUR_FORMAT)?;
    let camera = view::camera(project, shown.scene().metres_per_unit(), centre);
    let mapping = project.age.mapping();
    // (years, where) for every picture; the comparison's two halves have no file.
    let mut jobs: Vec<(f32, Option<PathBuf>)> = Vec::new();
    if let Some(path) = &r.image {
        jobs.push((mapping.years(t), Some(path.clone())));
    }
    if let Some((path, years)) = &r.sequence {
        jobs.extend(
            years
                .iter()
                .enumerate()
                .map(|(i, &y)| (y, Some(view::numbered(path, i)))),
        );
    }
    if let Some((_, [a, b])) = &r.compare {
        jobs.push((*a, None));
        jobs.push((*b, None));
    }
    let mut halves = Vec::new();
    let count = jobs.len() as f32;
    for (i, (years, path)) in jobs.into_iter().enumerate() {
        cancel.check()?;
        if !(0.0..=150.0).contains(&years) {
            bail!("render age {years} years: expected 0..=150");
        }
        progress(
            0.05 + 0.95 * i as f32 / count,
            &format!("rendering {years:.0} years"),
        );
        let t = mapping.t(years);
        shown.bake_and_upload(&mut renderer, t)?;
        let img = renderer.render_to_image(&shown.frame_params(t, camera), r.size)?;
        match path {
            Some(path) => stage_png(set, &path, &img)?,
            None => halves.push((years, img)),
        }
    }
    if let Some((path, _)) = &r.compare {
        let labelled: Vec<(String, image::RgbaImage)> = halves
            .into_iter()
            .map(|(y, img)| (format!("{y:.0}Y"), img))
            .collect();
        stage_png(set, path, &view::side_by_side(labelled))?;
    }
    Ok(())
}

fn stage_png(set: &OutputSet, path: &Path, img: &image::RgbaImage) -> anyhow::Result<()> {
    set.stage(path, |w| {
        out::encode_png(
            w,
            img.width(),
            img.height(),
            out::PngPixels::Rgba8,
            img.as_raw(),
        )
    })?;
    Ok(())
}

/// `dir/head.glb` → `dir/head{suffix}.{ext}`.
fn sibling(path: &Path, suffix: &str, ext: &str) -> PathBuf {
    let stem = path
        .file_stem()
        .map_or_else(String::new, |s| s.to_string_lossy().into_owned());
    path.with_file_name(format!("{stem}{suffix}.{ext}"))
}
