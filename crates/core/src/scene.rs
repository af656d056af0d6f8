//! One pipeline from a project to everything the editor, the renderer and the command line
//! show or write (issue 9): a [`Scene`] loads a project's inputs once and bakes, at a size
//! and an age, into buffers it keeps.
//!
//! **Incremental.** Every stage remembers the inputs it was made from and is redone only
//! when they change; [`Scene::bake`] returns which outputs changed ([`Changed`]):
//!
//! | stage | redone when |
//! |---|---|
//! | inputs (mesh, wrinkle files, masks, tile image) | their path changes ([`Scene::set_project`]) |
//! | large-wrinkle fibre stamps ([`LargeLayer`]) | a fibre changes: only that fibre is rasterised |
//! | large-wrinkle map at age t | the stamps, an age factor, γ, depth, mask, normal strength |
//! | micro-relief features (pores, furrows) | seed, map size, tiling, `pores`, `furrows` |
//! | micro-relief tile at age t | the features, noise, warp, overlap, normal, its age scales |
//! | fine-wrinkle tile | the `fine` section |
//! | transition texture | the hair masks, metric, size |
//! | hair instances | the mesh, the transition texture, density, seed, graying range |
//!
//! An age change only re-weights the large-wrinkle stamps and re-scales the micro-relief
//! features (their positions stay): no feature is regenerated.
//!
//! **Cancellable.** Every stage checks a [`CancelToken`] often (per row band); a cancelled
//! bake returns [`Error::Cancelled`] and the kept outputs are those of the last complete
//! bake of each stage (stages bake into scratch buffers and swap on success).
//!
//! **Deterministic.** Each stage is deterministic on any thread count, so the incremental
//! result equals a fresh scene's bake byte for byte (tested).

use std::path::{Path, PathBuf};
use std::sync::Arc;

use crate::age::{AgeCurve, AgeFactors};
use crate::cancel::CancelToken;
use crate::error::Error;
use crate::fine_wrinkles::{self, FineWrinkleSettings};
use crate::hair::{HairInstances, HairParams, SurfaceRef};
use crate::heightmap::HeightMap;
use crate::large_layer::LargeLayer;
use crate::mask::Mask;
use crate::mesh::Mesh;
use crate::micro::MicroRelief;
use crate::muscle::{Fibre, MaskValues};
use crate::normal_map::{self, NormalSettings};
use crate::project::{BuiltinMesh, Project};
use crate::transition::TransitionTexture;
use crate::wrinkle_file::{self, ParseErrors, WrinkleFile};

/// A wrinkle description file as the scene holds it: where it came from and its groups.
#[derive(Clone, Debug, PartialEq)]
pub struct WrinkleSource {
    /// The path, or the repository path of a built-in default file.
    pub name: String,
    /// `None` for the built-in default files.
    pub path: Option<PathBuf>,
    pub file: WrinkleFile,
}

/// What to bake. Sizes are square map sides in pixels.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct BakeRequest {
    /// Side of the large-wrinkle map (head UV).
    pub large_size_px: u32,
    /// Side of the micro-relief tile (the skin patch of `map_size_mm`).
    pub micro_size_px: u32,
    /// The age t ∈ [0, 1].
    pub t: f32,
    /// Also make the fine-wrinkle tile.
    pub fine: bool,
    /// Also make the transition texture and the hair instances.
    pub hair: bool,
    /// Also make the SPEC §4 RGBA8 packing of the large-wrinkle map (for the renderer).
    pub packed: bool,
    /// A one-off bake (`agesim bake`, exports): the large-wrinkle map is made in one pass
    /// without keeping per-fibre stamps or the sampled mask for later edits — the same
    /// bytes with less memory touched. A later bake of the same scene still works; it
    /// rasterises the stamps then.
    pub one_off: bool,
    /// Also make the micro-relief tile's 8-bit normal map (`MicroTile::normal_rgb`), for
    /// showing it: the renderer and the exports make their normals from the heights.
    /// Without it the editor's tiles (up to 1024²) leave `normal_rgb` empty; larger tiles
    /// always have it.
    pub micro_normals: bool,
}

impl BakeRequest {
    /// Everything the renderer shows, at preview sizes. The renderer reads the heights,
    /// so no RGBA packing (ask for it only to show it).
    pub fn preview(t: f32) -> Self {
        Self {
            large_size_px: 1024,
            micro_size_px: 1024,
            t,
            fine: true,
            hair: true,
            packed: false,
            one_off: false,
            micro_normals: false,
        }
    }

    /// The maps of `agesim bake`: one size, no hair, no packing, one-off.
    pub fn maps(size_px: u32, t: f32) -> Self {
        Self {
            large_size_px: size_px,
            micro_size_px: size_px,
            t,
            fine: false,
            hair: false,
            packed: false,
            one_off: true,
            // The exports make their normal map from the summed heights.
            micro_normals: false,
        }
    }
}

/// Which outputs a [`Scene::bake`] (or a setter) changed.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct Changed {
    pub mesh: bool,
    /// Large-wrinkle stamps (fibres rasterised).
    pub large_stamps: bool,
    /// The large-wrinkle map (and its packing).
    pub large: bool,
    /// Micro-relief features regenerated (pores placed, furrows linked).
    pub micro_features: bool,
    /// The micro-relief tile.
    pub micro: bool,
    pub fine: bool,
    pub transition: bool,
    pub hair: bool,
}

impl Changed {
    /// Whether anything changed.
    pub fn any(&self) -> bool {
        *self != Self::default()
    }

    fn merge(&mut self, o: Changed) {
        self.mesh |= o.mesh;
        self.large_stamps |= o.large_stamps;
        self.large |= o.large;
        self.micro_features |= o.micro_features;
        self.micro |= o.micro;
        self.fine |= o.fine;
        self.transition |= o.transition;
        self.hair |= o.hair;
    }
}

/// The large-wrinkle map at an age: heights in height units (depth × the normalised
/// layer) and, when asked for, the SPEC §4 RGBA8 packing with heights mapped from
/// [0, depth] to [0, 1].
#[derive(Clone, Debug)]
pub struct LargeMap {
    pub height: HeightMap,
    pub packed_rgba: Vec<u8>,
    /// The height range `packed_rgba`'s alpha spans.
    pub packed_range: (f32, f32),
}

/// The micro-relief tile at an age: heights and their RGB8 normal map (SPEC §4).
#[derive(Clone, Debug)]
pub struct MicroTile {
    pub height: HeightMap,
    /// The tile's 8-bit normal map; empty unless asked for (`BakeRequest::micro_normals`).
    pub normal_rgb: Vec<u8>,
}

/// Everything loaded from files (or the built-in defaults), kept until a path changes.
#[derive(Clone, Debug)]
struct Inputs {
    mesh_key: (Option<PathBuf>, BuiltinMesh),
    mesh: Arc<Mesh>,
    wrinkles_key: Vec<PathBuf>,
    wrinkles: Vec<WrinkleSource>,
    /// Whether `wrinkles` came from [`Scene::set_wrinkles`] rather than the files.
    wrinkles_edited: bool,
    large_mask_key: (Option<PathBuf>, bool),
    large_mask: Option<Arc<Mask>>,
    hair_masks_key: (Option<PathBuf>, Option<PathBuf>),
    hair_masks: Option<Arc<(Mask, Mask)>>,
    fine_tile_key: Option<PathBuf>,
    fine_tile: Option<Arc<HeightMap>>,
    /// Bumped whenever any input above changes (fibre edits included).
    generation: u64,
}

/// The keys each kept output was made from (see the module table).
#[derive(Clone, Debug, Default, PartialEq)]
struct LargeKey {
    layer_fibres: Vec<Fibre>,
    size: u32,
    factors: Vec<f32>,
    gamma: f32,
    depth: f32,
    mask_generation: u64,
    normal: Option<NormalSettings>,
    packed: bool,
}

#[derive(Clone, Debug, PartialEq)]
struct MicroKey {
    project: Project,
    scales: (f32, f32),
    size: u32,
    normals: bool,
}

#[derive(Clone, Debug, PartialEq)]
struct HairKey {
    mesh_generation: u64,
    transition_generation: u64,
    density: f32,
    metres_per_unit: f32,
    seed: u64,
    deviation_deg: f32,
    onset_t: (f32, f32),
}

/// A project, its loaded inputs and everything baked from them. See the module docs.
#[derive(Clone, Debug)]
pub struct Scene {
    project: Project,
    inputs: Inputs,
    mesh_generation: u64,
    mask_generation: u64,
    factors: AgeFactors,
    large: LargeStage,
    micro: MicroStage,
    fine_key: Option<(FineWrinkleSettingsKey, u64)>,
    fine: Option<Arc<HeightMap>>,
    transition_key: Option<(u64, String, Option<u32>)>,
    transition_generation: u64,
    transition: Option<Arc<TransitionTexture>>,
    hair_key: Option<HairKey>,
    hair: Option<Arc<HairInstances>>,
}

type FineWrinkleSettingsKey = (Option<PathBuf>, u32, u32, f32, f32, f32, f32, u64);

impl Scene {
    /// Loads every input of `project` (files it names, or the built-in defaults). Nothing
    /// is baked yet; call [`Scene::bake`].
    pub fn new(project: Project) -> Result<Self, Error> {
        project.validate().map_err(|message| Error::Project {
            source_name: "project".into(),
            message,
        })?;
        let inputs = Inputs::load(&project, None)?;
        let factors = project.age.factors(project.age.t, &[]);
        Ok(Self {
            project,
            inputs,
            mesh_generation: 1,
            mask_generation: 1,
            factors,
            large: LargeStage::default(),
            micro: MicroStage::default(),
            fine_key: None,
            fine: None,
            transition_key: None,
            transition_generation: 0,
            transition: None,
            hair_key: None,
            hair: None,
        })
    }

    /// A scene of the same project and inputs, sharing this one's reference-counted
    /// outputs (fine tile, transition texture, hair: kept while their keys hold) but none
    /// of its large-wrinkle and micro-relief buffers. For baking the same document at
    /// another size (the editor's previews beside its full-resolution bakes) without
    /// copying maps that the other size would replace anyway.
    pub fn fork(&self) -> Self {
        Self {
            project: self.project.clone(),
            inputs: self.inputs.clone(),
            mesh_generation: self.mesh_generation,
            mask_generation: self.mask_generation,
            factors: self.factors.clone(),
            large: LargeStage::default(),
            micro: MicroStage::default(),
            fine_key: self.fine_key.clone(),
            fine: self.fine.clone(),
            transition_key: self.transition_key.clone(),
            transition_generation: self.transition_generation,
            transition: self.transition.clone(),
            hair_key: self.hair_key.clone(),
            hair: self.hair.clone(),
        }
    }

    pub fn project(&self) -> &Project {
        &self.project
    }

    /// Replaces the project. Inputs whose paths changed are loaded again (all errors of
    /// all inputs are reported together); on error the scene is unchanged.
    pub fn set_project(&mut self, project: Project) -> Result<Changed, Error> {
        project.validate().map_err(|message| Error::Project {
            source_name: "project".into(),
            message,
        })?;
        let inputs = Inputs::load(&project, Some(&self.inputs))?;
        let mut changed = Changed::default();
        if !Arc::ptr_eq(&inputs.mesh, &self.inputs.mesh) {
            self.mesh_generation += 1;
            changed.mesh = true;
        }
        let same_mask = match (&inputs.large_mask, &self.inputs.large_mask) {
            (Some(a), Some(b)) => Arc::ptr_eq(a, b),
            (None, None) => true,
            _ => false,
        };
        if !same_mask {
            self.mask_generation += 1;
        }
        self.inputs = inputs;
        self.project = project;
        Ok(changed)
    }

    /// The wrinkle files the large-wrinkle layer is made of.
    pub fn wrinkles(&self) -> &[WrinkleSource] {
        &self.inputs.wrinkles
    }

    /// Replaces the wrinkle files' contents (the editor's fibre edits); the next bake
    /// re-rasterises only the fibres that differ.
    pub fn set_wrinkles(&mut self, wrinkles: Vec<WrinkleSource>) {
        if wrinkles != self.inputs.wrinkles {
            self.inputs.wrinkles = wrinkles;
            self.inputs.generation += 1;
            self.inputs.wrinkles_edited = true;
        }
    }

    /// Goes back to the wrinkle files the project names, as they are on disk (or the
    /// built-in ones), after [`Scene::set_wrinkles`]; nothing is read when there was no
    /// edit.
    pub fn reset_wrinkles(&mut self) -> Result<(), Error> {
        if self.inputs.wrinkles_edited {
            let files = load_wrinkles(&self.inputs.wrinkles_key)?;
            self.set_wrinkles(files);
            self.inputs.wrinkles_edited = false;
        }
        Ok(())
    }

    /// Every fibre with its own age curve (`None` = the layer default), in order.
    pub fn fibres(&self) -> (Vec<Fibre>, Vec<Option<AgeCurve>>) {
        self.inputs
            .wrinkles
            .iter()
            .flat_map(|w| w.file.groups.iter())
            .map(|g| (g.fibre.clone(), g.age))
            .unzip()
    }

    pub fn mesh(&self) -> &Arc<Mesh> {
        &self.inputs.mesh
    }

    /// The large-wrinkle mask in use (the project's, or the default head's with its
    /// default wrinkle files), if any.
    pub fn large_mask(&self) -> Option<&Arc<Mask>> {
        self.inputs.large_mask.as_ref()
    }

    /// The age factors of the last bake.
    pub fn factors(&self) -> &AgeFactors {
        &self.factors
    }

    /// The large-wrinkle map of the last bake (`None` before the first, or when the layer
    /// is disabled).
    pub fn large(&self) -> Option<&LargeMap> {
        self.large.map.as_ref()
    }

    /// The micro-relief tile of the last bake.
    pub fn micro(&self) -> Option<&MicroTile> {
        self.micro.tile.as_ref()
    }

    /// The micro-relief features (pores, furrows) of the last bake.
    pub fn relief(&self) -> Option<&MicroRelief> {
        self.micro.relief.as_ref()
    }

    /// The fine-wrinkle tile of the last bake that asked for it.
    pub fn fine(&self) -> Option<&Arc<HeightMap>> {
        self.fine.as_ref()
    }

    pub fn transition(&self) -> Option<&Arc<TransitionTexture>> {
        self.transition.as_ref()
    }

    /// The hair instances, sorted by disappearance age; draw the first `count(t)`.
    pub fn hair(&self) -> Option<&Arc<HairInstances>> {
        self.hair.as_ref()
    }

    /// Whether the project bakes any micro-relief at all.
    pub fn micro_enabled(&self) -> bool {
        let p = &self.project;
        p.pores.enabled || p.furrows.enabled || (p.noise.details > 0.0 && p.noise.strength > 0.0)
    }

    /// The project's normal-map settings.
    pub fn normal_settings(&self) -> NormalSettings {
        NormalSettings {
            strength: self.project.normal.strength,
            convention: self.project.normal.convention,
            tiling: self.project.tile,
        }
    }

    /// Bakes what `request` asks for at its age, redoing only what changed since the last
    /// bake. On error (or cancellation) every kept output stays as it was.
    pub fn bake(&mut self, request: &BakeRequest, cancel: &CancelToken) -> Result<Changed, Error> {
        crate::heightmap::check_size(request.large_size_px, request.micro_size_px)?;
        let (fibres, curves) = self.fibres();
        self.factors = self.project.age.factors(request.t, &curves);
        let mut changed = Changed::default();
        let normal = self.normal_settings();
        let micro_enabled = self.micro_enabled();
        let (large, micro) = (&mut self.large, &mut self.micro);
        let (project, inputs, factors) = (&self.project, &self.inputs, &self.factors);
        let mask_generation = self.mask_generation;
        // The two layers are independent: bake them side by side (each is itself
        // parallel; together they keep both cores busy through each one's serial parts).
        let (large_result, micro_result) = rayon::join(
            || {
                if project.large.enabled {
                    let mask = LargeMask {
                        mask: inputs.large_mask.as_deref(),
                        generation: mask_generation,
                    };
                    large.bake(project, &fibres, factors, mask, request, &normal, cancel)
                } else {
                    Ok(large.clear())
                }
            },
            || {
                if micro_enabled {
                    micro.bake(project, factors, request, &normal, cancel)
                } else {
                    Ok(micro.clear())
                }
            },
        );
        changed.merge(large_result?);
        changed.merge(micro_result?);
        if request.fine && self.project.fine.enabled {
            changed.merge(self.bake_fine(cancel)?);
        }
        if request.hair && self.project.hair.enabled {
            changed.merge(self.bake_hair(cancel)?);
        }
        Ok(changed)
    }

    fn bake_fine(&mut self, cancel: &CancelToken) -> Result<Changed, Error> {
        let f = &self.project.fine;
        let key: FineWrinkleSettingsKey = (
            f.tile.clone(),
            f.size_px,
            f.creases,
            f.length,
            f.width,
            f.crossing_deg,
            f.spread_deg,
            f.seed,
        );
        let key = (key, self.inputs.generation_of_fine());
        if self.fine_key.as_ref() == Some(&key) && self.fine.is_some() {
            return Ok(Changed::default());
        }
        cancel.check()?;
        let tile = match &self.inputs.fine_tile {
            Some(image) => image.clone(),
            None => Arc::new(fine_wrinkles::generate(
                f.size_px,
                &FineWrinkleSettings {
                    crease_count: f.creases,
                    length_tile: f.length,
                    width_tile: f.width,
                    crossing_deg: f.crossing_deg,
                    spread_deg: f.spread_deg,
                    seed: f.seed,
                },
            )?),
        };
        self.fine = Some(tile);
        self.fine_key = Some(key);
        Ok(Changed {
            fine: true,
            ..Changed::default()
        })
    }

    fn bake_hair(&mut self, cancel: &CancelToken) -> Result<Changed, Error> {
        let mut changed = Changed::default();
        let h = &self.project.hair;
        let Some(masks) = self.inputs.hair_masks.clone() else {
            return Ok(changed);
        };
        let masks_id = Arc::as_ptr(&masks) as u64;
        let tkey = (masks_id, format!("{:?}", h.metric), h.transition_size_px);
        if self.transition_key.as_ref() != Some(&tkey) || self.transition.is_none() {
            cancel.check()?;
            let (outer, inner) = &*masks;
            // An all-black outer mask means no hair at age 0; it is almost surely the
            // wrong file, and would leave only the inner region's hair: say so.
            if outer
                .values()
                .iter()
                .all(|&v| v < crate::transition::REGION_THRESHOLD)
            {
                return Err(Error::InvalidValue {
                    what: format!(
                        "outer hair mask {}",
                        h.outer_mask
                            .as_ref()
                            .map_or("(built-in)".into(), |p| p.display().to_string())
                    ),
                    value: "empty (no pixel at or above 50 % grey)".into(),
                    expected: "white where hair grows at age 0".into(),
                });
            }
            let size = h.transition_size_px.unwrap_or_else(|| {
                outer
                    .width_px()
                    .max(outer.height_px())
                    .max(inner.width_px())
                    .max(inner.height_px())
            });
            let t = TransitionTexture::from_masks(outer, inner, size, size, h.metric)?;
            self.transition = Some(Arc::new(t));
            self.transition_key = Some(tkey);
            self.transition_generation += 1;
            changed.transition = true;
        }
        let key = HairKey {
            mesh_generation: self.mesh_generation,
            transition_generation: self.transition_generation,
            density: h.density_per_cm2,
            metres_per_unit: self.project.mesh.metres_per_unit,
            seed: h.seed,
            deviation_deg: h.max_deviation_deg,
            onset_t: self.project.graying_onset_t(),
        };
        if self.hair_key.as_ref() == Some(&key) && self.hair.is_some() {
            return Ok(changed);
        }
        cancel.check()?;
        let Some(transition) = &self.transition else {
            return Ok(changed);
        };
        let params = HairParams::new(h.density_per_cm2, self.project.mesh.metres_per_unit)?
            .with_seed(h.seed)
            .with_max_deviation_rad(h.max_deviation_deg.to_radians())?
            .with_graying_onset_range(key.onset_t.0, key.onset_t.1)?;
        let mesh = &self.inputs.mesh;
        let surface =
            SurfaceRef::new(mesh.positions(), mesh.normals(), mesh.uvs(), mesh.indices())?;
        let hair = HairInstances::generate(&surface, transition, &params)?;
        self.hair = Some(Arc::new(hair));
        self.hair_key = Some(key);
        changed.hair = true;
        Ok(changed)
    }

    /// The height and normal maps `agesim bake` writes: the micro-relief and the
    /// large-wrinkle map added pixel by pixel (both baked at the same size; a layer that is
    /// off adds nothing), and the RGB8 normal map of the sum.
    pub fn export_maps(&self) -> Result<(HeightMap, Vec<u8>), Error> {
        self.export_size()?;
        let height = match (&self.micro.tile, &self.large.map) {
            (Some(m), large) => {
                let mut height = m.height.clone();
                if let Some(l) = large {
                    add_into(&mut height, &l.height);
                }
                height
            }
            (None, Some(l)) => l.height.clone(),
            (None, None) => return Err(no_layer()),
        };
        let rgb = normal_map::encode_rgb8(&height, &self.normal_settings())?;
        Ok((height, rgb))
    }

    /// The exported height map of a one-off bake (`agesim bake`, exports; the normal map
    /// is then streamed from it, [`crate::export::stage_normal_png`]): the kept maps are
    /// moved out, not copied (at 4096² a copy is 64 MB of fresh memory). The scene forgets
    /// them; a later bake makes them again. The same heights as [`Scene::export_maps`].
    pub fn take_height(&mut self) -> Result<HeightMap, Error> {
        self.export_size()?;
        self.micro.key = None;
        self.large.key = None;
        let micro = self.micro.tile.take().map(|m| m.height);
        let large = self.large.map.take().map(|l| l.height);
        let (mut height, large) = match (micro, large) {
            (Some(m), l) => (m, l),
            (None, Some(l)) => (l, None),
            (None, None) => return Err(no_layer()),
        };
        if let Some(large) = large {
            add_into(&mut height, &large);
        }
        Ok(height)
    }

    /// The side of the exported maps: the tile's or the large map's (they must agree).
    fn export_size(&self) -> Result<u32, Error> {
        let size = match (&self.micro.tile, &self.large.map) {
            (Some(m), _) => m.height.width_px(),
            (None, Some(l)) => l.height.width_px(),
            (None, None) => return Err(no_layer()),
        };
        if let Some(large) = &self.large.map
            && large.height.width_px() != size
        {
            return Err(Error::InvalidValue {
                what: "export size".into(),
                value: format!("{} and {size}", large.height.width_px()),
                expected: "the large-wrinkle and micro-relief maps baked at one size".into(),
            });
        }
        Ok(size)
    }
}

/// h += l, pixel by pixel.
fn add_into(height: &mut HeightMap, large: &HeightMap) {
    for (h, l) in height.data_mut().iter_mut().zip(large.data()) {
        *h += l;
    }
}

/// The error of an export with no layer baked.
fn no_layer() -> Error {
    Error::InvalidValue {
        what: "bake".into(),
        value: "no layer".into(),
        expected: "at least one enabled layer (large wrinkles, pores, furrows or noise)".into(),
    }
}

/// The large-wrinkle stage: fibre stamps, the map at an age, its packing.
#[derive(Clone, Debug, Default)]
struct LargeStage {
    layer: LargeLayer,
    key: Option<LargeKey>,
    map: Option<LargeMap>,
    /// The previous map's buffer, baked into next (no allocation, no page faults).
    spare: Option<HeightMap>,
    /// The mask sampled at the map's pixel centres: (mask generation, size, values).
    mask_samples: Option<(u64, u32, Arc<Vec<f32>>)>,
}

/// The large-wrinkle mask and the generation that identifies it.
#[derive(Clone, Copy)]
struct LargeMask<'a> {
    mask: Option<&'a Mask>,
    generation: u64,
}

impl LargeStage {
    /// Drops the map (the layer is off).
    fn clear(&mut self) -> Changed {
        self.key = None;
        Changed {
            large: self.map.take().is_some(),
            ..Changed::default()
        }
    }

    #[allow(clippy::too_many_arguments)]
    fn bake(
        &mut self,
        p: &Project,
        fibres: &[Fibre],
        factors: &AgeFactors,
        large_mask: LargeMask<'_>,
        request: &BakeRequest,
        normal: &NormalSettings,
        cancel: &CancelToken,
    ) -> Result<Changed, Error> {
        let mut changed = Changed::default();
        let size = request.large_size_px;
        if !request.one_off {
            changed.large_stamps = self.layer.update(fibres, size, size, cancel)? > 0;
        }
        let key = LargeKey {
            layer_fibres: fibres.to_vec(),
            size,
            factors: factors.large.clone(),
            gamma: p.large.gamma,
            depth: p.large.depth,
            mask_generation: large_mask.generation,
            normal: request.packed.then_some(*normal),
            packed: request.packed,
        };
        if self.key.as_ref() == Some(&key) && self.map.is_some() {
            return Ok(changed);
        }
        // A one-off bake samples the mask from its taps (no map-sized buffer kept); the
        // editor's bakes keep the samples for the next change.
        let columns = match (request.one_off, large_mask.mask) {
            (true, Some(m)) => crate::muscle::mask_columns(m, size),
            _ => Vec::new(),
        };
        let mask_samples = match (large_mask.mask, &self.mask_samples) {
            (None, _) => None,
            _ if request.one_off => None,
            (Some(_), Some((g, s, v))) if *g == large_mask.generation && *s == size => {
                Some(v.clone())
            }
            (Some(mask), _) => {
                let v = Arc::new(crate::muscle::sample_mask(mask, size, size));
                self.mask_samples = Some((large_mask.generation, size, v.clone()));
                Some(v)
            }
        };
        let mask = match (&mask_samples, large_mask.mask) {
            (Some(v), _) => MaskValues::Values(v),
            (None, Some(m)) if request.one_off => MaskValues::Taps(m, &columns),
            _ => MaskValues::None,
        };
        // The spare buffer, not the kept map: that stays whole if this bake is cancelled.
        let mut height = match self.spare.take() {
            Some(h) if h.width_px() == size && h.height_px() == size => h,
            _ => HeightMap::zeros(size, size)?,
        };
        let gamma = p.large.gamma;
        let baked = if request.one_off {
            // One pass, no stamps (`large_layer::bake_direct`: the same bytes).
            crate::large_layer::bake_direct(
                fibres,
                &factors.large,
                gamma,
                mask,
                &mut height,
                cancel,
            )
        } else {
            self.layer
                .combine_with(&factors.large, gamma, mask, &mut height, cancel)
        };
        if let Err(e) = baked {
            self.spare = Some(height);
            return Err(e);
        }
        self.keep(height, p.large.depth, request, normal, key, cancel)?;
        changed.large = true;
        Ok(changed)
    }

    /// Scales a finished map by the depth, packs it if asked and keeps it as the map.
    fn keep(
        &mut self,
        mut height: HeightMap,
        depth: f32,
        request: &BakeRequest,
        normal: &NormalSettings,
        key: LargeKey,
        cancel: &CancelToken,
    ) -> Result<(), Error> {
        if depth != 1.0 {
            for h in height.data_mut() {
                *h *= depth;
            }
        }
        cancel.check()?;
        let packed_range = (0.0, depth.max(f32::MIN_POSITIVE));
        let packed_rgba = if request.packed {
            normal_map::pack_rgba8(&height, normal, packed_range)?
        } else {
            Vec::new()
        };
        cancel.check()?;
        let previous = self.map.replace(LargeMap {
            height,
            packed_rgba,
            packed_range,
        });
        self.spare = previous.map(|l| l.height);
        self.key = Some(key);
        Ok(())
    }
}

/// Tiles up to this side keep their features and their noise as separate maps (the
/// editor's preview and full tiles), so an age change re-bakes only the features and a
/// noise change only the noise; larger tiles (one-off exports) bake in one fused pass.
const SPLIT_MAX_PX: u32 = 1024;

/// The micro-relief stage: features and the tile at an age.
#[derive(Clone, Debug, Default)]
struct MicroStage {
    relief: Option<MicroRelief>,
    key: Option<MicroKey>,
    tile: Option<MicroTile>,
    /// The previous tile's buffers, baked into next.
    spare: Option<MicroTile>,
    /// The tile's features alone (pores and furrows at the age scales), and its key.
    features: Option<(Project, (f32, f32), u32, HeightMap)>,
    /// The tile's noise alone, and its key.
    noise: Option<(Project, u32, HeightMap)>,
}

/// The fields the micro-relief noise depends on.
fn noise_relevant(p: &Project) -> Project {
    Project {
        seed: p.seed,
        map_size_mm: p.map_size_mm,
        tile: p.tile,
        noise: p.noise.clone(),
        ..Project::default()
    }
}

/// The fields the micro-relief features depend on (all but the noise and normals).
fn features_relevant(p: &Project) -> Project {
    Project {
        noise: Project::default().noise,
        normal: Project::default().normal,
        ..micro_relevant(p)
    }
}

impl MicroStage {
    /// Drops the tile (no micro-relief layer is on).
    fn clear(&mut self) -> Changed {
        self.key = None;
        Changed {
            micro: self.tile.take().is_some(),
            ..Changed::default()
        }
    }

    fn bake(
        &mut self,
        project: &Project,
        factors: &AgeFactors,
        request: &BakeRequest,
        normal: &NormalSettings,
        cancel: &CancelToken,
    ) -> Result<Changed, Error> {
        let mut changed = Changed::default();
        let mut relief = match &self.relief {
            Some(r) => {
                let (r, regenerated) = r.with_settings(&project.micro_settings()?)?;
                changed.micro_features = regenerated;
                r
            }
            None => {
                changed.micro_features = true;
                project.micro_relief()?
            }
        };
        let scales = (factors.pore_radius_scale, factors.furrow_depth_scale);
        relief.set_age_scales(scales.0, scales.1);
        let key = MicroKey {
            project: micro_relevant(project),
            scales,
            size: request.micro_size_px,
            normals: request.micro_normals || request.micro_size_px > SPLIT_MAX_PX,
        };
        if self.key.as_ref() == Some(&key) && self.tile.is_some() {
            self.relief = Some(relief);
            return Ok(changed);
        }
        cancel.check()?;
        let size = request.micro_size_px;
        // Into the spare buffers (the previous tile's, or fresh zeroed pages).
        let mut spare = match self.spare.take() {
            Some(t) if t.height.width_px() == size => t,
            _ => MicroTile {
                height: HeightMap::zeros(size, size)?,
                normal_rgb: crate::heightmap::zeroed_vec(
                    size as usize * size as usize * 3,
                    "normal map",
                )?,
            },
        };
        let baked = if size <= SPLIT_MAX_PX {
            let normal = key.normals.then_some(normal);
            self.bake_split(&relief, project, scales, size, normal, &mut spare, cancel)
        } else {
            relief
                .bake_into_cancellable(
                    size,
                    &mut spare.height,
                    &mut spare.normal_rgb,
                    normal,
                    cancel,
                )
                .map(|_| ())
        };
        if let Err(e) = baked {
            self.spare = Some(spare);
            return Err(e);
        }
        self.relief = Some(relief);
        self.spare = self.tile.replace(spare);
        self.key = Some(key);
        changed.micro = true;
        Ok(changed)
    }

    /// The tile as features + noise from the kept parts, re-baking only the part whose
    /// key changed, then its normal map if `normal` is given (else `normal_rgb` is left
    /// empty): the same bytes as the fused pass.
    #[allow(clippy::too_many_arguments)]
    fn bake_split(
        &mut self,
        relief: &MicroRelief,
        project: &Project,
        scales: (f32, f32),
        size: u32,
        normal: Option<&NormalSettings>,
        out: &mut MicroTile,
        cancel: &CancelToken,
    ) -> Result<(), Error> {
        use crate::micro::bake::Parts;
        use rayon::prelude::*;
        let features_key = (features_relevant(project), scales, size);
        let features_valid = self
            .features
            .as_ref()
            .is_some_and(|(p, sc, sz, _)| (p, *sc, *sz) == (&features_key.0, scales, size));
        let noise_key = (noise_relevant(project), size);
        let noise_valid = self
            .noise
            .as_ref()
            .is_some_and(|(p, sz, _)| (p, *sz) == (&noise_key.0, size));
        let (mut features, mut noise) = (self.features.take(), self.noise.take());
        let result = (|| {
            // Features and noise at once when both are needed (each pass is parallel too).
            let bake = |part: Parts, kept: Option<HeightMap>| -> Result<HeightMap, Error> {
                let mut map = match kept {
                    Some(m) => m,
                    None => HeightMap::zeros(size, size)?,
                };
                relief.bake_parts_into(size, part, &mut map, cancel)?;
                Ok(map)
            };
            let only = |features: bool| Parts {
                features,
                noise: !features,
            };
            // A stale part's buffer is baked over (no fresh pages to fault in).
            let stale_f = (!features_valid).then(|| features.take().map(|(.., m)| m));
            let stale_n = (!noise_valid).then(|| noise.take().map(|(.., m)| m));
            let (f, n) = rayon::join(
                || stale_f.map(|kept| bake(only(true), kept)).transpose(),
                || stale_n.map(|kept| bake(only(false), kept)).transpose(),
            );
            if let Some(f) = f? {
                features = Some((features_key.0.clone(), scales, size, f));
            }
            if let Some(n) = n? {
                noise = Some((noise_key.0.clone(), size, n));
            }
            let (Some((.., f)), Some((.., n))) = (&features, &noise) else {
                return Err(Error::Cancelled);
            };
            if out.height.width_px() != size || out.height.height_px() != size {
                out.height = HeightMap::zeros(size, size)?;
            }
            out.height
                .data_mut()
                .par_chunks_mut(size as usize)
                .zip(f.data().par_chunks(size as usize))
                .zip(n.data().par_chunks(size as usize))
                .for_each(|((h, f), n)| {
                    for ((h, f), n) in h.iter_mut().zip(f).zip(n) {
                        *h = f + n;
                    }
                });
            cancel.check()?;
            match normal {
                Some(normal) => normal_map::encode_rgb8_into(
                    &out.height,
                    normal,
                    crate::simd::Level::detect(),
                    &mut out.normal_rgb,
                ),
                None => {
                    out.normal_rgb.clear();
                    Ok(())
                }
            }
        })();
        // Each kept part carries its own key, so what was baked before an error stays.
        self.features = features;
        self.noise = noise;
        result
    }
}

/// The project with only the fields the micro-relief tile depends on (for its key).
fn micro_relevant(p: &Project) -> Project {
    Project {
        seed: p.seed,
        map_size_mm: p.map_size_mm,
        tile: p.tile,
        pores: p.pores.clone(),
        furrows: p.furrows.clone(),
        noise: p.noise.clone(),
        warp: p.warp.clone(),
        overlap: p.overlap.clone(),
        normal: p.normal.clone(),
        ..Project::default()
    }
}

impl Inputs {
    fn generation_of_fine(&self) -> u64 {
        self.fine_tile.as_ref().map_or(0, |t| Arc::as_ptr(t) as u64)
    }

    /// Loads what `project` names, reusing `previous`'s inputs whose key is unchanged.
    /// Every failing input is reported (wrinkle files with all their diagnostics).
    fn load(project: &Project, previous: Option<&Inputs>) -> Result<Self, Error> {
        let mesh_key = (project.mesh.path.clone(), project.mesh.builtin);
        let wrinkles_key = project.large.wrinkles.clone();
        let large_mask_key = (
            project.large.mask.clone(),
            project.large.wrinkles.is_empty(),
        );
        let hair_masks_key = (
            project.hair.outer_mask.clone(),
            project.hair.inner_mask.clone(),
        );
        let fine_tile_key = project.fine.tile.clone();
        // The inputs are independent: decoded at once on the pool (the mesh and the
        // masks are most of a bake's start-up). Errors are reported in this fixed order.
        let load_mesh_part = || match previous.filter(|p| p.mesh_key == mesh_key) {
            Some(p) => Ok(p.mesh.clone()),
            None => load_mesh(project).map(Arc::new),
        };
        let load_wrinkles_part = || match previous.filter(|p| p.wrinkles_key == wrinkles_key) {
            Some(p) => Ok((p.wrinkles.clone(), p.wrinkles_edited)),
            None => load_wrinkles(&wrinkles_key).map(|w| (w, false)),
        };
        let load_large_mask_part = || match previous.filter(|p| p.large_mask_key == large_mask_key)
        {
            Some(p) => Ok(p.large_mask.clone()),
            None => load_large_mask(&large_mask_key).map(|m| m.map(Arc::new)),
        };
        let load_hair_part = || match previous.filter(|p| p.hair_masks_key == hair_masks_key) {
            Some(p) => (Ok(p.hair_masks.clone()), Ok(())),
            None => {
                let (outer, inner) = rayon::join(
                    || {
                        load_mask_or(
                            hair_masks_key.0.as_deref(),
                            crate::defaults::HAIR_OUTER_MASK,
                        )
                    },
                    || {
                        load_mask_or(
                            hair_masks_key.1.as_deref(),
                            crate::defaults::HAIR_INNER_MASK,
                        )
                    },
                );
                match (outer, inner) {
                    (Ok(o), Ok(i)) => (Ok(Some(Arc::new((o, i)))), Ok(())),
                    (o, i) => (o.map(|_| None), i.map(|_| ())),
                }
            }
        };
        let load_fine_part = || match previous.filter(|p| p.fine_tile_key == fine_tile_key) {
            Some(p) => Ok(p.fine_tile.clone()),
            None => match &fine_tile_key {
                None => Ok(None),
                Some(path) => Mask::load(path)
                    .and_then(|m| {
                        HeightMap::from_vec(m.width_px(), m.height_px(), m.values().to_vec())
                    })
                    .map(|h| Some(Arc::new(h))),
            },
        };
        let (mesh, ((wrinkles, large_mask), ((hair_masks, inner_error), fine_tile))) =
            rayon::join(load_mesh_part, || {
                rayon::join(
                    || rayon::join(load_wrinkles_part, load_large_mask_part),
                    || rayon::join(load_hair_part, load_fine_part),
                )
            });
        let mut errors: Vec<Error> = Vec::new();
        let mut ok = |r: Result<(), Error>| errors.extend(r.err());
        let mesh = mesh.map_err(|e| ok(Err(e))).ok();
        let (wrinkles, wrinkles_edited) = match wrinkles {
            Ok((w, edited)) => (Some(w), edited),
            Err(e) => {
                ok(Err(e));
                (None, false)
            }
        };
        let large_mask = large_mask.map_err(|e| ok(Err(e))).ok();
        let hair_masks = hair_masks.map_err(|e| ok(Err(e))).ok();
        ok(inner_error);
        let fine_tile = fine_tile.map_err(|e| ok(Err(e))).ok();
        match (mesh, wrinkles, large_mask, hair_masks, fine_tile) {
            (Some(mesh), Some(wrinkles), Some(large_mask), Some(hair_masks), Some(fine_tile))
                if errors.is_empty() =>
            {
                let generation = previous.map_or(0, |p| p.generation)
                    + u64::from(previous.is_none_or(|p| p.wrinkles != wrinkles));
                Ok(Self {
                    mesh_key,
                    mesh,
                    wrinkles_key,
                    wrinkles,
                    wrinkles_edited,
                    large_mask_key,
                    large_mask,
                    hair_masks_key,
                    hair_masks,
                    fine_tile_key,
                    fine_tile,
                    generation,
                })
            }
            _ if errors.len() == 1 => Err(errors.remove(0)),
            _ => Err(Error::Inputs(
                errors.iter().map(ToString::to_string).collect(),
            )),
        }
    }
}

fn load_mesh(project: &Project) -> Result<Mesh, Error> {
    match (&project.mesh.path, project.mesh.builtin) {
        (Some(path), _) => Mesh::load(path),
        (None, BuiltinMesh::Head) => Ok(crate::head::default_head()),
        (None, BuiltinMesh::SkinPatch) => Ok(crate::head::skin_patch()),
    }
}

/// The wrinkle files at `paths` (the built-in defaults when empty), every diagnostic of
/// every file reported together.
pub fn load_wrinkles(paths: &[PathBuf]) -> Result<Vec<WrinkleSource>, Error> {
    let mut loaded = Vec::new();
    let mut diagnostics = Vec::new();
    let mut push = |name: String,
                    path: Option<PathBuf>,
                    result: Result<WrinkleFile, ParseErrors>| {
        match result {
            Ok(file) => loaded.push(WrinkleSource { name, path, file }),
            Err(errors) => diagnostics.extend(errors.0),
        }
    };
    if paths.is_empty() {
        for (name, text) in crate::defaults::WRINKLE_FILES {
            push(
                name.to_string(),
                None,
                wrinkle_file::parse(text, Path::new(name)),
            );
        }
    } else {
        for path in paths {
            let bytes = crate::limits::read_file(path, crate::limits::MAX_TEXT_FILE_BYTES)?;
            push(
                path.display().to_string(),
                Some(path.clone()),
                wrinkle_file::parse_bytes(&bytes, path),
            );
        }
    }
    if diagnostics.is_empty() {
        Ok(loaded)
    } else {
        Err(Error::WrinkleFile(ParseErrors(diagnostics)))
    }
}

/// The large-wrinkle mask: the named one, or the default head's when the default wrinkle
/// files are used, or none.
fn load_large_mask(key: &(Option<PathBuf>, bool)) -> Result<Option<Mask>, Error> {
    match key {
        (Some(path), _) => Mask::load(path).map(Some),
        (None, true) => {
            let (name, bytes) = crate::defaults::WRINKLE_MASK;
            Mask::decode(bytes, Path::new(name)).map(Some)
        }
        (None, false) => Ok(None),
    }
}

fn load_mask_or(path: Option<&Path>, default: (&str, &[u8])) -> Result<Mask, Error> {
    match path {
        Some(p) => Mask::load(p),
        None => Mask::decode(default.1, Path::new(default.0)),
    }
}

#[cfg(test)]
mod tests;
