//! Exports at an age, shared by `agesim export` and the editor's Export window: the maps
//! (height as 16-bit PNG and 32-bit EXR, normal PNG), renders (one image, an age sequence,
//! a young | old comparison) and the aged head as GLB.
//!
//! Everything one request writes is one output set (`agesim_core::export::OutputSet`):
//! each file goes to a temporary first, and only when every file is written are they all
//! renamed into place. An error or a cancel leaves the old files whole and no temporary.

use std::path::{Path, PathBuf};

use agesim_core::cancel::CancelToken;
use agesim_core::export::OutputSet;
use agesim_core::mesh::gltf::{GlbMaterial, write_glb_with_material};
use agesim_core::normal_map::Convention;
use agesim_core::project::Project;
use agesim_core::scene::{BakeRequest, Scene, WrinkleSource};
use agesim_core::{HeightMap, export as out, heightmap};
use anyhow::{Context as _, bail};
use glam::Vec3;

/// The maps of `agesim bake` (the large wrinkles on the head's UV plus the micro-relief
/// over the whole square), at one size.
#[derive(Clone, Debug, Default)]
pub struct MapsOut {
    pub size_px: u32,
    pub height_png: Option<PathBuf>,
    pub height_exr: Option<PathBuf>,
    pub normal_png: Option<PathBuf>,
    /// The normal map's green channel; `None`: the project's `normal.convention`.
    pub convention: Option<Convention>,
    /// Bake the micro-relief periodic, so the maps tile (the skin patch).
    pub tileable: bool,
    /// The height EXR's (lossless) compression.
    pub exr_compression: agesim_core::export::ExrCompression,
}

impl MapsOut {
    fn any(&self) -> bool {
        self.height_png.is_some() || self.height_exr.is_some() || self.normal_png.is_some()
    }
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
    /// Every file the request writes, in order.
    pub fn outputs(&self) -> Vec<PathBuf> {
        let m = &self.maps;
        let mut files: Vec<PathBuf> = [&m.height_png, &m.height_exr, &m.normal_png]
            .into_iter()
            .flatten()
            .cloned()
            .collect();
        if let Some(g) = &self.glb {
            files.push(g.path.clone());
            files.push(g.height_path());
        }
        let r = &self.renders;
        files.extend(r.image.iter().cloned());
        if let Some((path, years)) = &r.sequence {
            files.extend((0..years.len()).map(|i| numbered(path, i)));
        }
        files.extend(r.compare.iter().map(|(p, _)| p.clone()));
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
    if request.maps.any() {
        let (start, share) = step(0);
        let p = |f: f32, what: &str| progress(start + share * f, what);
        export_maps(project, wrinkles, t, &request.maps, &set, &p, cancel)?;
    }
    if let Some(glb) = &request.glb {
        let (start, share) = step(1);
        let p = |f: f32, what: &str| progress(start + share * f, what);
        export_glb(project, wrinkles, t, request.years, glb, &set, &p, cancel)?;
    }
    if r.any() {
        let (start, share) = step(2);
        let p = |f: f32, what: &str| progress(start + share * f, what);
        export_renders(project, wrinkles, t, r, &set, &p, cancel)?;
    }
    cancel.check()?;
    progress(1.0, "putting the files in place");
    set.commit()?;
    Ok(outputs)
}

/// A scene of `project` with the edited wrinkle files.
fn scene(project: Project, wrinkles: Option<&[WrinkleSource]>) -> anyhow::Result<Scene> {
    let mut scene = Scene::new(project)?;
    if let Some(w) = wrinkles {
        scene.set_wrinkles(w.to_vec());
    }
    Ok(scene)
}

fn export_maps(
    project: &Project,
    wrinkles: Option<&[WrinkleSource]>,
    t: f32,
    maps: &MapsOut,
    set: &OutputSet,
    progress: Progress<'_>,
    cancel: &CancelToken,
) -> anyhow::Result<()> {
    let mut p = project.clone();
    p.tile = maps.tileable;
    if let Some(c) = maps.convention {
        p.normal.convention = c;
    }
    progress(0.0, "loading the inputs");
    let mut scene = scene(p, wrinkles)?;
    progress(0.1, "baking the maps");
    scene.bake(&BakeRequest::maps(maps.size_px, t), cancel)?;
    let height = scene.take_height()?;
    let normal = scene.normal_settings();
    cancel.check()?;
    progress(0.6, "writing the maps");
    out::stage_maps(
        set,
        out::MapPaths {
            height_png: maps.height_png.as_deref(),
            height_exr: maps.height_exr.as_deref(),
            normal_png: maps.normal_png.as_deref(),
        },
        &height,
        &normal,
        maps.exr_compression,
    )?;
    Ok(())
}

#[allow(clippy::too_many_arguments)]
fn export_glb(
    project: &Project,
    wrinkles: Option<&[WrinkleSource]>,
    t: f32,
    years: f32,
    glb: &GlbOut,
    set: &OutputSet,
    progress: Progress<'_>,
    cancel: &CancelToken,
) -> anyhow::Result<()> {
    let mut p = project.clone();
    // The tiles repeat over the head: they must wrap.
    p.tile = true;
    progress(0.0, "loading the head");
    let mut scene = scene(p, wrinkles)?;
    progress(0.1, "baking the head's maps");
    let request = BakeRequest {
        large_size_px: glb.size_px,
        micro_size_px: 1024.min(glb.size_px.max(64)),
        t,
        fine: true,
        hair: false,
        packed: false,
        one_off: true,
        micro_normals: false,
    };
    scene.bake(&request, cancel)?;
    progress(0.5, "composing the normal map");
    let normals = head_normal_map(&scene, glb.size_px, cancel)?;
    progress(0.7, "encoding the textures");
    let mut png = Vec::new();
    out::encode_png(
        &mut png,
        glb.size_px,
        glb.size_px,
        out::PngPixels::Rgb8,
        &normals,
    )
    .context("encoding the normal map")?;
    cancel.check()?;
    let project = scene.project();
    let params = crate::frame::frame_params(
        project,
        scene.factors(),
        crate::frame::camera(project, Vec3::ZERO),
    );
    let large = scene.large().map(|l| &l.height);
    let height_name = glb
        .height_path()
        .file_name()
        .map(|n| n.to_string_lossy().into_owned())
        .unwrap_or_default();
    let range = large.map(|h| h.min_max());
    let a = params.skin.albedo;
    let material = GlbMaterial {
        name: format!("agesim skin, {years:.0} years"),
        base_colour: [a.x, a.y, a.z, 1.0],
        roughness: 0.42,
        metallic: 0.0,
        normal_png: Some(png),
        extras: serde_json::json!({
            "agesim_version": env!("CARGO_PKG_VERSION"),
            "age_years": years,
            "age_t": t,
            "height_map": height_name,
            "height_range": range.map(|(lo, hi)| [lo, hi]),
            "height_meaning": "large-wrinkle height = lo + (hi - lo) * p / 65535 for a 16-bit value p, in the project's height units (large.depth = deepest)",
        }),
    };
    let bytes = write_glb_with_material(scene.mesh(), Some(&material));
    progress(0.9, "writing the GLB");
    set.stage(&glb.path, |w| std::io::Write::write_all(w, &bytes))?;
    let flat;
    let height = match large {
        Some(h) => h,
        None => {
            flat = HeightMap::zeros(glb.size_px, glb.size_px)?;
            &flat
        }
    };
    out::stage_height_png16(set, &glb.height_path(), height)?;
    Ok(())
}

/// The head's tangent-space normal map at the scene's age, OpenGL convention (green =
/// +v), RGB8, `size_px`² over the head's UV square: the CPU twin of `shaders/skin.wgsl`'s
/// `shade` without parallax. Large wrinkles from their heights with `view.disp_scale`
/// (SPEC §4); the fine-wrinkle tile in the large wrinkles' frame, blended by the age
/// (SPEC §5); the micro-relief tile on top by reoriented normal mapping. The tiles repeat
/// a whole number of times across the UV square, as in the renderer, and are box-filtered
/// to about one texel per output pixel first (the GPU's mip level).
pub fn head_normal_map(
    scene: &Scene,
    size_px: u32,
    cancel: &CancelToken,
) -> anyhow::Result<Vec<u8>> {
    use rayon::prelude::*;
    let project = scene.project();
    let mesh = scene.mesh();
    let scale = agesim_render::SurfaceScale::measure(mesh.positions(), mesh.uvs(), mesh.indices())
        .context("the mesh's UVs are degenerate: no normal map can be laid on it")?;
    let mpu = project.mesh.metres_per_unit;
    let n = size_px as usize;
    // Large-wrinkle heights in [0, 1] (÷ depth), as uploaded to the renderer.
    let large: Option<(Vec<f32>, usize)> = scene.large().map(|l| {
        let inv = if project.large.depth > 0.0 {
            1.0 / project.large.depth
        } else {
            0.0
        };
        (
            l.height.data().iter().map(|h| h * inv).collect(),
            l.height.width_px() as usize,
        )
    });
    let disp = project.view.disp_scale;
    let fine_blend = if project.fine.enabled {
        scene.factors().fine_blend.clamp(0.0, 1.0)
    } else {
        0.0
    };
    let micro_on = project.pores.enabled || project.furrows.enabled || project.noise.strength > 0.0;
    let tile =
        |map: Option<&HeightMap>, size_m: f32, strength: f32| -> anyhow::Result<Option<Placed>> {
            let Some(map) = map else { return Ok(None) };
            let repeats = scale.repeats(mpu, size_m.max(1e-6));
            // Texels of the tile per output pixel; box-filter down to about one.
            let per_px = map.width_px() as f32 * repeats[0].max(repeats[1]) / n as f32;
            let side = map.width_px().min(map.height_px());
            let factor = (1..=(per_px.floor() as u32).clamp(1, side))
                .rev()
                .find(|f| map.width_px() % f == 0 && map.height_px() % f == 0)
                .unwrap_or(1);
            let filtered = if factor > 1 {
                map.downsample_box(factor)?
            } else {
                map.clone()
            };
            let tile = Tile::new(&filtered, repeats, strength);
            Ok(Some(Placed {
                columns: tile.taps(size_px, false),
                rows: tile.taps(size_px, true),
                tile,
            }))
        };
    let micro = if micro_on {
        tile(
            scene.micro().map(|m| &m.height),
            project.map_size_mm * 1e-3,
            project.normal.strength,
        )?
    } else {
        None
    };
    let fine = if fine_blend > 0.0 {
        tile(
            scene.fine().map(|f| f.as_ref()),
            project.fine.size_mm * 1e-3,
            project.fine.strength,
        )?
    } else {
        None
    };
    let mut rgb = vec![0u8; n * n * 3];
    rgb.par_chunks_mut(n * 3).enumerate().try_for_each(
        |(y, row)| -> Result<(), agesim_core::Error> {
            if y % 64 == 0 {
                cancel.check()?;
            }
            for (x, px) in row.chunks_exact_mut(3).enumerate() {
                let n_large = match &large {
                    Some((h, side)) => {
                        // Central differences in texels of the large map (row 0 = top, v up).
                        // The texel under the pixel (the map is baked at `size_px`, so
                        // usually the same one), its neighbours clamped at the border.
                        let s = *side;
                        let (lx, ly) = (x * s / n, y * s / n);
                        let row = |y: usize| &h[y * s..(y + 1) * s];
                        let (left, right) = (lx.saturating_sub(1), (lx + 1).min(s - 1));
                        let (up, down) = (ly.saturating_sub(1), (ly + 1).min(s - 1));
                        let here = row(ly);
                        let du = (here[right] - here[left]) * 0.5 * s as f32;
                        let dv = (row(up)[lx] - row(down)[lx]) * 0.5 * s as f32;
                        Vec3::new(-disp * du, -disp * dv, 1.0).normalize()
                    }
                    None => Vec3::Z,
                };
                let mut n_ts = n_large;
                if let Some(f) = &fine {
                    let nf = f.tile.normal(f.columns[x], f.rows[y]);
                    let t = Vec3::new(n_large.z, 0.0, -n_large.x).normalize();
                    let b = Vec3::new(0.0, n_large.z, -n_large.y).normalize();
                    let in_frame = (t * nf.x + b * nf.y + n_large * nf.z).normalize();
                    n_ts = n_large.lerp(in_frame, fine_blend).normalize();
                }
                if let Some(m) = &micro {
                    n_ts = rnm(n_ts, m.tile.normal(m.columns[x], m.rows[y]));
                }
                for (c, value) in px.iter_mut().zip(n_ts.to_array()) {
                    *c = agesim_core::normal_map::encode_unorm8(value * 0.5 + 0.5);
                }
            }
            Ok(())
        },
    )?;
    Ok(rgb)
}

/// A tile with its column and row taps on the output map.
struct Placed {
    tile: Tile,
    columns: Vec<(usize, usize, f32)>,
    rows: Vec<(usize, usize, f32)>,
}

/// A height tile repeated over the UV square, for [`head_normal_map`]: its tangent-space
/// normals (SPEC §4 by central differences on the wrapped tile) made once per texel, then
/// interpolated per output pixel.
struct Tile {
    normals: Vec<Vec3>,
    width: usize,
    height: usize,
    repeats: [f32; 2],
}

impl Tile {
    fn new(map: &HeightMap, repeats: [f32; 2], strength: f32) -> Self {
        let (w, h) = (map.width_px() as usize, map.height_px() as usize);
        let d = map.data();
        let mut normals = Vec::with_capacity(w * h);
        for y in 0..h {
            let (up, down) = ((y + h - 1) % h, (y + 1) % h);
            for x in 0..w {
                let (left, right) = ((x + w - 1) % w, (x + 1) % w);
                // Row 0 is the top (v up): +v is the row above.
                let du = (d[y * w + right] - d[y * w + left]) * 0.5 * w as f32;
                let dv = (d[up * w + x] - d[down * w + x]) * 0.5 * h as f32;
                normals.push(Vec3::new(-strength * du, -strength * dv, 1.0).normalize());
            }
        }
        Self {
            normals,
            width: w,
            height: h,
            repeats,
        }
    }

    /// Where each output column (or row) of a `size_px` map falls on the repeated tile:
    /// (texel, next texel, weight of the next), wrapping. Made once per map, so the
    /// per-pixel work is four loads and two lerps.
    fn taps(&self, size_px: u32, along_v: bool) -> Vec<(usize, usize, f32)> {
        let (side, repeats) = if along_v {
            (self.height, self.repeats[1])
        } else {
            (self.width, self.repeats[0])
        };
        (0..size_px)
            .map(|i| {
                let t = if along_v {
                    // Row 0 is the top (v up).
                    1.0 - (heightmap::pixel_to_v(i, size_px) * repeats).fract()
                } else {
                    (heightmap::pixel_to_u(i, size_px) * repeats).fract()
                };
                let t = t * side as f32 - 0.5;
                let t0 = t.floor();
                let i0 = if t0 < 0.0 {
                    side - 1
                } else {
                    (t0 as usize).min(side - 1)
                };
                (i0, if i0 + 1 == side { 0 } else { i0 + 1 }, t - t0)
            })
            .collect()
    }

    /// The normal between the four texels of a column tap and a row tap.
    #[inline]
    fn normal(&self, (x0, x1, fx): (usize, usize, f32), (y0, y1, fy): (usize, usize, f32)) -> Vec3 {
        let (w, n) = (self.width, &self.normals);
        let top = n[y0 * w + x0].lerp(n[y0 * w + x1], fx);
        let bottom = n[y1 * w + x0].lerp(n[y1 * w + x1], fx);
        top.lerp(bottom, fy).normalize()
    }
}

/// Reoriented normal mapping (Barré-Brisebois & Hill 2012), as in `skin.wgsl`.
fn rnm(base: Vec3, detail: Vec3) -> Vec3 {
    let t = base + Vec3::Z;
    let u = detail * Vec3::new(-1.0, -1.0, 1.0);
    (t * t.dot(u) / t.z - u).normalize()
}

fn export_renders(
    project: &Project,
    wrinkles: Option<&[WrinkleSource]>,
    t: f32,
    r: &RendersOut,
    set: &OutputSet,
    progress: Progress<'_>,
    cancel: &CancelToken,
) -> anyhow::Result<()> {
    use agesim_render::{FrameParams, Gpu, Renderer};
    progress(0.0, "starting the renderer");
    let density = if project.hair.enabled {
        project.hair.density_per_cm2
    } else {
        0.0
    };
    let mut inputs = crate::cli::render::SceneInputs::gather(
        project,
        None,
        false,
        project.mesh.metres_per_unit,
        1024,
        density,
    )?;
    if let Some(w) = wrinkles {
        inputs.set_wrinkles(w.to_vec());
    }
    let gpu = Gpu::new()?;
    let mut renderer = Renderer::new(&gpu.device, &gpu.queue, agesim_render::COLOUR_FORMAT)?;
    let centre = inputs.mesh().bounds().centre();
    let camera = crate::frame::camera(project, centre);
    let mut params: FrameParams =
        crate::frame::frame_params(project, &project.age.factors(t, &[]), camera);
    let mapping = project.age.mapping();
    // (years, where, label?) for every picture, then the comparison's two halves.
    let mut jobs: Vec<(f32, Option<PathBuf>)> = Vec::new();
    if let Some(path) = &r.image {
        jobs.push((mapping.years(t), Some(path.clone())));
    }
    if let Some((path, years)) = &r.sequence {
        jobs.extend(
            years
                .iter()
                .enumerate()
                .map(|(i, &y)| (y, Some(numbered(path, i)))),
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
        inputs.upload_age(&mut renderer, mapping.t(years), &mut params)?;
        let img = renderer.render_to_image(&params, r.size)?;
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
        stage_png(set, path, &crate::cli::render::side_by_side(labelled))?;
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

/// FILE.png → FILE_0003.png.
pub fn numbered(out: &Path, i: usize) -> PathBuf {
    let stem = out
        .file_stem()
        .map_or_else(String::new, |s| s.to_string_lossy().into_owned());
    let ext = out
        .extension()
        .map_or_else(|| "png".into(), |e| e.to_string_lossy().into_owned());
    out.with_file_name(format!("{stem}_{i:04}.{ext}"))
}

/// `dir/head.glb` → `dir/head{suffix}.{ext}`.
fn sibling(path: &Path, suffix: &str, ext: &str) -> PathBuf {
    let stem = path
        .file_stem()
        .map_or_else(String::new, |s| s.to_string_lossy().into_owned());
    path.with_file_name(format!("{stem}{suffix}.{ext}"))
}
