//! Exports at an age, shared by `agesim export` and the editor's Export window: the maps
//! (height as 16-bit PNG and 32-bit EXR, normal PNG), renders (one image, an age sequence,
//! a young | old comparison) and the aged head as GLB.
//!
//! Everything one request writes is one output set (`agesim_core::output::export::OutputSet`):
//! each file goes to a temporary first, and only when every file is written are they all
//! renamed into place. An error or a cancel leaves the old files whole and no temporary.

use std::path::{Path, PathBuf};

use agesim_core::base::cancel::CancelToken;
use agesim_core::head::mesh::udim::Udim;
use agesim_core::maps::normal_map::Convention;
use agesim_core::output::export::OutputSet;
use agesim_core::project::Project;
use agesim_core::scene::{Scene, WrinkleSource};
use agesim_core::{maps::heightmap, output::export as out};
use anyhow::{Context as _, bail};

use crate::view;

mod glb;
mod maps;

use glb::export_glb;
pub use glb::{glb_bake_request, head_normal_map};
use maps::export_maps;
pub use maps::{BakedMaps, Wanted, bake_maps, crease_maps, stage_maps};

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
    /// The aged hair and brows in the GLB, as a mesh named `hair`.
    pub hair: GlbHair,
}

/// How much of the hair the GLB carries (docs/models.md §9 "The hair in the GLB").
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, serde::Serialize, serde::Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum GlbHair {
    /// No hair.
    None,
    /// One scalp hair in [`GlbHair::LIGHT_STRIDE`], each as wide as that many (the same
    /// cover, a quarter of the bytes); the brows and lashes whole.
    #[default]
    Light,
    /// Every hair the view draws.
    Full,
}

impl GlbHair {
    /// Of the scalp hairs, a light GLB carries one in this many.
    pub const LIGHT_STRIDE: usize = 4;

    /// One scalp hair in how many; `None`: no hair.
    pub fn stride(self) -> Option<usize> {
        match self {
            Self::None => None,
            Self::Light => Some(Self::LIGHT_STRIDE),
            Self::Full => Some(1),
        }
    }
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
/// u16 copy and its PNG byte buffer, the RGB normals, and the occlusion, roughness and
/// metallic (RGB) with a grey copy.
pub fn peak_bytes(size_px: u32) -> u64 {
    (size_px as u64).pow(2) * (4 + 4 + 2 + 2 + 3 + 4)
}

/// Refuses a map size outside the engine's range, or one this machine's free memory
/// cannot hold, before any work starts; `what` names the setting in the message.
pub fn check_map_size(size_px: u32, what: &str) -> anyhow::Result<()> {
    heightmap::check_size(size_px, size_px).with_context(|| format!("{what} {size_px}"))?;
    if let Some(available) = agesim_core::base::limits::available_memory_bytes() {
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
