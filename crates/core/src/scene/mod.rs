//! One pipeline from a project to everything the editor, the renderer and the command line
//! show or write: a [`Scene`] loads a project's inputs once and bakes, at a size
//! and an age, into buffers it keeps.
//!
//! **Incremental.** Every stage remembers the inputs it was made from and is redone only
//! when they change; [`Scene::bake`] returns which outputs changed ([`Changed`]):
//!
//! | stage | redone when |
//! |---|---|
//! | inputs (mesh, wrinkle files, masks, tile image) | their path changes ([`Scene::set_project`]) |
//! | large-wrinkle fibre stamps ([`LargeLayer`](crate::layers::wrinkles::large_layer::LargeLayer)) | a fibre changes: only that fibre is rasterised |
//! | large-wrinkle map at age t | the stamps, an age factor, γ, mask (and, for its RGBA packing, depth and normal strength) |
//! | micro-relief features (pores, furrows) | seed, map size, tiling, `pores`, `furrows` |
//! | micro-relief tile at age t | the features, noise, warp, overlap, normal, its age scales |
//! | fine-wrinkle tile | the `fine` section |
//! | transition texture | the hair masks, metric, size |
//! | hair instances | the mesh, the transition texture, density, seed, graying range |
//!
//! An age change only re-weights the large-wrinkle stamps and re-scales the micro-relief
//! features (their positions stay): no feature is regenerated. The large-wrinkle map is
//! kept normalised: its depth (`large.depth`) is applied where it is shown (the exported
//! heights, the renderer's relief depth), so a depth change bakes nothing.
//!
//! **Cancellable.** Every stage checks a [`CancelToken`] often (per row band); a cancelled
//! bake returns [`Error::Cancelled`] and the kept outputs are those of the last complete
//! bake of each stage (stages bake into scratch buffers and swap on success).
//!
//! **Deterministic.** Each stage is deterministic on any thread count, so the incremental
//! result equals a fresh scene's bake byte for byte (tested).

mod bake;
mod colour;
mod export;
mod hair;
mod inputs;
mod large;
mod micro;
mod own;
mod shape;
mod shown;
mod units;

pub use inputs::{AUTO_FIT_MAX_MEDIAN_MM, HeadLayout, load_wrinkles};
pub use own::{BROW_DARKNESS, FALLBACK_HAIR, LossChoice, Person, Source, describe_measured};
pub use shape::AgedShape;
pub use units::units_of;

use std::path::PathBuf;
use std::sync::Arc;

use crate::age::{AgeCurve, AgeFactors};
use crate::base::arc_key::ArcKey;
use crate::base::cancel::CancelToken;
use crate::base::error::Error;
use crate::head::fit::Correspondence;
use crate::head::landmarks::Landmarks;
use crate::head::mesh::Mesh;
use crate::layers::hair::transition::TransitionTexture;
use crate::layers::hair::{HairInstances, HairParams, SurfaceRef};
use crate::layers::micro::MicroRelief;
use crate::layers::shape::relief::ShapeRelief;
use crate::layers::wrinkles::fine_wrinkles::{self, FineWrinkleSettings};
use crate::layers::wrinkles::muscle::Fibre;
use crate::layers::wrinkles::wrinkle_file::WrinkleFile;
use crate::maps::heightmap::HeightMap;
use crate::maps::mask::Mask;
use crate::maps::normal_map::{self, NormalSettings};
use crate::project::Project;

use bake::{FineWrinkleSettingsKey, add_into, scaled};
use hair::{BrowHairsKey, BrowsKey, EyeHairs, HairKey, TransitionKey};
use inputs::Inputs;
use large::{LargeMask, LargeStage};
use micro::MicroStage;
use shape::{AgedShapeKey, ShapeKey};
use shown::{EyesKey, HairAlphaKey, ShownKey};

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
    /// Bake the micro-relief tile periodic (noise and features wrap around its edges) and
    /// its normals with wrapped differences: whatever repeats the tile over a surface (the
    /// renderer, the GLB's normal map) asks for it; `agesim bake` and map exports follow
    /// the project's `tile`.
    pub tileable: bool,
    /// Also make the fine-wrinkle tile.
    pub fine: bool,
    /// Also make the transition texture and the hair instances.
    pub hair: bool,
    /// Also make the docs/models.md §5 RGBA8 packing of the large-wrinkle map (a picture
    /// for the map view: the renderer reads the heights).
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
    /// Also add the shape's relief finer than the head's triangles to the large map
    /// ([`crate::layers::shape::relief`]): what the view and the exported head show. `agesim
    /// bake`'s maps are the wrinkles' alone (normalised: a full-depth wrinkle spans 1).
    pub shape_relief: bool,
}

impl BakeRequest {
    /// Everything the renderer shows, at preview sizes. The renderer reads the heights,
    /// so no RGBA packing (ask for it only to show it).
    pub fn preview(t: f32) -> Self {
        Self {
            large_size_px: 1024,
            micro_size_px: 1024,
            t,
            tileable: true,
            fine: true,
            hair: true,
            packed: false,
            one_off: false,
            micro_normals: false,
            shape_relief: true,
        }
    }

    /// The maps of `agesim bake`: one size, no hair, no packing, one-off; the micro-relief
    /// periodic when `tileable` (the project's `tile`).
    pub fn maps(size_px: u32, t: f32, tileable: bool) -> Self {
        Self {
            large_size_px: size_px,
            micro_size_px: size_px,
            t,
            tileable,
            fine: false,
            hair: false,
            packed: false,
            one_off: true,
            // The exports make their normal map from the summed heights.
            micro_normals: false,
            shape_relief: false,
        }
    }

    /// The hair alone at age `t` (its transition and placement; every map a texel): what
    /// `agesim hair` and `mesh-info --age` ask for.
    pub fn hair_only(t: f32) -> Self {
        Self {
            hair: true,
            ..Self::maps(1, t, false)
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

    /// Adds what `o` changed.
    pub fn merge(&mut self, o: Changed) {
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

/// The large-wrinkle map at an age: the normalised layer (multiply by the project's
/// `large.depth` for height units: [`LargeMap::scaled`]) and, when asked for, the RGBA8
/// packing of docs/models.md §4 of the scaled heights, mapped from [0, depth] to [0, 1].
#[derive(Clone, Debug)]
pub struct LargeMap {
    /// The normalised heights (a wrinkle of full depth spans 1), in the head's own UV
    /// layout.
    pub height: HeightMap,
    /// The age it was baked at, years: its heights are drawn `Project::large_depth_at`
    /// these years deep.
    pub years: f32,
    /// A fitted head's map in the template's layout, where the fibres are drawn (the map
    /// view's chart); `None` when the head reads the layers at its own UVs (`height` is
    /// then that chart).
    pub template: Option<HeightMap>,
    /// The packing, of the template's layout (the chart the fibres are edited on).
    pub packed_rgba: Vec<u8>,
    /// The height range `packed_rgba`'s alpha spans.
    pub packed_range: (f32, f32),
}

/// The micro-relief tile at an age: heights and their RGB8 normal map (docs/models.md §5).
#[derive(Clone, Debug)]
pub struct MicroTile {
    pub height: HeightMap,
    /// The tile's 8-bit normal map; empty unless asked for (`BakeRequest::micro_normals`).
    pub normal_rgb: Vec<u8>,
}

/// A project, its loaded inputs and everything baked from them. See the module docs.
#[derive(Clone, Debug)]
pub struct Scene {
    project: Project,
    inputs: Inputs,
    mesh_generation: u64,
    mask_generation: u64,
    factors: AgeFactors,
    /// The last request's `tileable` (before any bake: the project's `tile`).
    tileable: bool,
    large: LargeStage,
    micro: MicroStage,
    fine_key: Option<(FineWrinkleSettingsKey, Option<ArcKey<HeightMap>>)>,
    fine: Option<Arc<HeightMap>>,
    transition_key: Option<TransitionKey>,
    transition_generation: u64,
    transition: Option<Arc<TransitionTexture>>,
    hair_key: Option<HairKey>,
    hair: Option<Arc<HairInstances>>,
    colour: colour::ColourStage,
    /// The shape field and what it was made from (mesh and layout generations, metres per
    /// unit, strengths).
    shape: Option<(ShapeKey, Arc<crate::layers::shape::ShapeField>)>,
    /// The field a shape slider shows while it moves (the settled one's moves scaled to
    /// the new strengths, [`Scene::bake_shape_moving`]) and its key.
    shape_moving: Option<(ShapeKey, Arc<crate::layers::shape::ShapeField>)>,
    /// What the shape field is made on whatever the strengths (mesh and layout
    /// generations, metres per unit's bits).
    shape_basis: Option<((u64, u64, u32), Arc<crate::layers::shape::ShapeBasis>)>,
    /// The shape at the last [`Scene::bake_shape`]'s age, keyed by its field and years.
    /// The aged shape, keyed by its field, its age and whether its sky was measured.
    shape_aged: Option<(AgedShapeKey, Arc<AgedShape>)>,
    /// The shape's relief finer than the head's triangles, added to the large-wrinkle
    /// map ([`crate::layers::shape::relief`]), keyed like the field and by its map size.
    relief: Option<((ShapeKey, u32), Arc<ShapeRelief>)>,
    /// The brow hairs and lashes placed on the head, keyed by mesh and layout
    /// generations, metres per unit (bits) and seed.
    brows: Option<(BrowHairsKey, Arc<EyeHairs>)>,
    /// The head's own colours ([`Scene::own_colours`]) and what they were measured on.
    own: Option<(own::OwnKey, Arc<crate::layers::skin_colour::OwnColours>)>,
    /// Where the micro-relief lies ([`Scene::micro_weight`]), keyed by the mesh and layout
    /// generations; `None` inside: everywhere.
    micro_weight: Option<(
        micro::MicroWeightKey,
        Option<Arc<crate::maps::mask::HeadImage>>,
    )>,
    /// The brow hairs and lashes at the last [`Scene::bake_brows`]'s age, keyed by the
    /// hairs, the shape and the factors they were made from.
    brows_aged: Option<(BrowsKey, Arc<Vec<crate::layers::hair::brows::BrowStrand>>)>,
    /// The aged colour as the 3D view shows it ([`Scene::shown_colour`]), with the aged
    /// colour and the transition generation it was made from.
    shown: Option<(ShownKey, Arc<crate::maps::mask::HeadImage>)>,
    /// The blank eyeballs' texels the 3D view draws eyes on, keyed by the mesh and layout
    /// generations, the colour map (its identity) and the shown colour's size.
    eyes: Option<(EyesKey, Arc<crate::layers::skin_colour::EyeTexels>)>,
    /// The hair's ages as the shown colour's alpha
    /// ([`crate::layers::hair::scalp::hair_age_alpha`]), per transition generation and size.
    hair_alpha: Option<(HairAlphaKey, Arc<Vec<u8>>)>,
    /// Bumped when the head's layout (its fit) changes.
    layout_generation: u64,
    /// The warps that lay the `space=surface` wrinkle groups on the surface of the layout
    /// the large-wrinkle layer is baked in, each with the group it was made for and that
    /// layout (`None`: the template's; else the head's mesh generation; see
    /// [`Scene::laid_on_surface`]).
    surface_warps: Vec<(
        Fibre,
        Option<u64>,
        Option<Arc<crate::layers::wrinkles::surface_warp::SurfaceWarp>>,
    )>,
    /// The correspondence maps of the current layout, by size (the large map's and the
    /// transition texture's).
    correspondences: Vec<Arc<Correspondence>>,
    /// Which content of each input file is wanted ([`Scene::set_file_versions`]).
    versions: FileVersions,
    /// Earlier inputs whose files' contents differ from the current ones, newest first
    /// (at most [`PAST_INPUTS`]): an older version asked for again (an undone reload) is
    /// taken from here, as it was, not read again.
    past: Vec<Inputs>,
}

/// Which content of each input file (mesh, masks, tile, landmarks, colour and normal
/// maps) a scene uses: a file changed on disk is given a new number by the caller, and
/// asking for an earlier number again gives that earlier content while the scene still
/// holds it. A path not listed is version 0.
pub type FileVersions = std::collections::BTreeMap<PathBuf, u64>;

/// Past input states a scene keeps for [`FileVersions`].
const PAST_INPUTS: usize = 8;

impl Scene {
    /// Loads every input of `project` (files it names, or the built-in defaults). Nothing
    /// is baked yet; call [`Scene::bake`].
    pub fn new(project: Project) -> Result<Self, Error> {
        Self::new_showing(project, &mut |_| {})
    }

    /// [`Scene::new`], giving `shown` the head as soon as it is read and turned upright,
    /// before its landmarks are found and the template fitted to it (seconds on a dense
    /// head): what a viewer shows while the rest is made.
    pub fn new_showing(project: Project, shown: &mut dyn FnMut(&Arc<Mesh>)) -> Result<Self, Error> {
        project.validate().map_err(|message| Error::Project {
            source_name: "project".into(),
            message,
        })?;
        let inputs = Inputs::load(&project, &FileVersions::new(), &[], shown)?;
        let factors = project.age.factors(project.age.t, &[]);
        Ok(Self {
            tileable: project.tile,
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
            colour: colour::ColourStage::default(),
            shape: None,
            shape_basis: None,
            shape_moving: None,
            shape_aged: None,
            relief: None,
            brows: None,
            own: None,
            micro_weight: None,
            brows_aged: None,
            shown: None,
            eyes: None,
            hair_alpha: None,
            layout_generation: 1,
            surface_warps: Vec::new(),
            correspondences: Vec::new(),
            versions: FileVersions::new(),
            past: Vec::new(),
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
            tileable: self.tileable,
            large: LargeStage::default(),
            micro: MicroStage::default(),
            fine_key: self.fine_key.clone(),
            fine: self.fine.clone(),
            transition_key: self.transition_key.clone(),
            transition_generation: self.transition_generation,
            transition: self.transition.clone(),
            hair_key: self.hair_key.clone(),
            hair: self.hair.clone(),
            colour: self.colour.clone(),
            shape: self.shape.clone(),
            shape_basis: self.shape_basis.clone(),
            shape_moving: self.shape_moving.clone(),
            shape_aged: self.shape_aged.clone(),
            relief: self.relief.clone(),
            brows: self.brows.clone(),
            own: self.own.clone(),
            micro_weight: self.micro_weight.clone(),
            brows_aged: self.brows_aged.clone(),
            shown: self.shown.clone(),
            eyes: self.eyes.clone(),
            hair_alpha: self.hair_alpha.clone(),
            layout_generation: self.layout_generation,
            surface_warps: self.surface_warps.clone(),
            correspondences: self.correspondences.clone(),
            versions: self.versions.clone(),
            past: self.past.clone(),
        }
    }

    pub fn project(&self) -> &Project {
        &self.project
    }

    /// Replaces the project. Inputs whose paths changed are loaded again (all errors of
    /// all inputs are reported together); on error the scene is unchanged.
    pub fn set_project(&mut self, project: Project) -> Result<Changed, Error> {
        self.set_project_showing(project, &mut |_| {})
    }

    /// [`Scene::set_project`], giving `shown` a new head as soon as it is read and turned
    /// upright ([`Scene::new_showing`]).
    pub fn set_project_showing(
        &mut self,
        project: Project,
        shown: &mut dyn FnMut(&Arc<Mesh>),
    ) -> Result<Changed, Error> {
        project.validate().map_err(|message| Error::Project {
            source_name: "project".into(),
            message,
        })?;
        let inputs = Inputs::load(&project, &self.versions, &self.kept(), shown)?;
        Ok(self.adopt(inputs, project))
    }

    /// Sets which content of each input file to use (the mesh, the masks, the
    /// fine-wrinkle tile, the landmarks, the colour and normal maps; [`FileVersions`]): a
    /// new version is read from the file, an earlier one still held is used as it was.
    /// On error the scene is unchanged. Wrinkle files are the caller's
    /// ([`Scene::set_wrinkles`]).
    pub fn set_file_versions(&mut self, versions: &FileVersions) -> Result<Changed, Error> {
        if *versions == self.versions {
            return Ok(Changed::default());
        }
        let inputs = Inputs::load(&self.project, versions, &self.kept(), &mut |_| {})?;
        self.versions = versions.clone();
        Ok(self.adopt(inputs, self.project.clone()))
    }

    /// The input states to reuse from: the current one, then the past ones.
    fn kept(&self) -> Vec<&Inputs> {
        std::iter::once(&self.inputs).chain(&self.past).collect()
    }

    /// Takes `inputs` and `project`, saying what changed for the stages.
    fn adopt(&mut self, inputs: Inputs, project: Project) -> Changed {
        let mut changed = Changed::default();
        if !Arc::ptr_eq(&inputs.mesh, &self.inputs.mesh) {
            self.mesh_generation += 1;
            changed.mesh = true;
            // What was made on the last mesh's vertices is not this one's (a dense head's
            // first look, before its shape, showed the last head's aged shape).
            (self.shape_aged, self.brows_aged) = (None, None);
        }
        let same_mask = match (&inputs.large_mask, &self.inputs.large_mask) {
            (Some(a), Some(b)) => Arc::ptr_eq(a, b),
            (None, None) => true,
            _ => false,
        };
        if !same_mask {
            self.mask_generation += 1;
        }
        if !Arc::ptr_eq(&inputs.layout, &self.inputs.layout) {
            self.layout_generation += 1;
            self.correspondences.clear();
        }
        let old = std::mem::replace(&mut self.inputs, inputs);
        if !old.same_files(&self.inputs) {
            self.past.retain(|p| !p.same_files(&old));
            self.past.insert(0, old);
            self.past.truncate(PAST_INPUTS);
        }
        self.project = project;
        changed
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

    /// Cells per side of the head's UDIM atlas (1 for a single-tile head).
    pub(crate) fn udim_grid(&self) -> u32 {
        self.inputs.mesh.udim().map_or(1, |u| u.grid())
    }

    /// The mesh as its file gives it (its own axes, every part), before the scene turned
    /// it and chose its skin.
    pub fn file_mesh(&self) -> &Arc<Mesh> {
        &self.inputs.raw_mesh
    }

    /// `fibres` with their warps attached: each `space=surface` group laid on the surface
    /// of the layout the large-wrinkle layer is baked in (the template's for a fitted
    /// head, `template` true; the head's own otherwise). A warp is made once per group
    /// and layout; groups that cannot be laid (see [`SurfaceWarp::new`]) stay in UV.
    ///
    /// [`SurfaceWarp::new`]: crate::layers::wrinkles::surface_warp::SurfaceWarp::new
    fn laid_on_surface(&mut self, fibres: Vec<Fibre>, template: bool) -> Vec<Fibre> {
        use crate::layers::wrinkles::muscle::Space;
        use crate::layers::wrinkles::surface_warp::SurfaceWarp;
        if fibres.iter().all(|f| f.space() == Space::Uv) {
            self.surface_warps.clear();
            return fibres;
        }
        let (mesh, layout): (&Mesh, _) = if template {
            (&crate::head::fit::template().mesh, None)
        } else {
            (&self.inputs.mesh, Some(self.mesh_generation))
        };
        let mut kept = std::mem::take(&mut self.surface_warps);
        let mut laid = Vec::with_capacity(fibres.len());
        for fibre in fibres {
            if fibre.space() == Space::Uv {
                laid.push(fibre);
                continue;
            }
            let found = kept
                .iter()
                .position(|(f, l, _)| *l == layout && *f == fibre);
            let warp = match found {
                Some(i) => kept.swap_remove(i).2,
                None => SurfaceWarp::new(fibre.capsule_bounds_uv(), mesh).map(Arc::new),
            };
            self.surface_warps
                .push((fibre.clone(), layout, warp.clone()));
            laid.push(fibre.with_warp(warp));
        }
        laid
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

    /// The mesh file's up and forward axes; the scene's mesh is turned to agesim's
    /// (+Y up, +Z forward).
    pub fn axes(&self) -> crate::head::mesh::units::Axes {
        self.inputs.axes
    }

    /// How [`Scene::axes`] were decided: set in the project, from the landmarks, found by
    /// fitting the template, or assumed.
    pub fn axes_how(&self) -> &str {
        &self.inputs.axes_how
    }

    /// The head's landmarks, when the project names a landmark file (`mesh.landmarks`).
    pub fn landmarks(&self) -> Option<&Landmarks> {
        self.inputs.landmarks.as_deref()
    }

    /// The head's base colour map (`mesh.colour_map`, else the one the mesh file's
    /// material names), over its own UVs.
    pub fn colour_map(&self) -> Option<&Arc<crate::maps::mask::HeadImage>> {
        self.inputs
            .colour_map
            .as_ref()
            .or(self.inputs.file_textures.colour.as_ref())
    }

    /// Where the mesh file's own pictures came from (its material's colour and normal
    /// maps), for reports; empty when it names none.
    pub fn file_textures(&self) -> &[String] {
        &self.inputs.file_textures.sources
    }

    /// The picture files the mesh file's material names (read with the mesh: a change to
    /// one is a new version of the mesh file, [`FileVersions`]).
    pub fn file_texture_paths(&self) -> &[PathBuf] {
        &self.inputs.file_textures.files
    }

    /// The head's tangent-space normal map (`mesh.normal_map`, else the one the mesh
    /// file's material names), over its own UVs.
    pub fn normal_map(&self) -> Option<&Arc<crate::maps::mask::HeadImage>> {
        self.inputs
            .normal_map
            .as_ref()
            .or(self.inputs.file_textures.normal.as_ref())
    }

    /// How the mesh reads the layers: the template fitted to it, or its own UVs, and why.
    pub fn layout(&self) -> &HeadLayout {
        &self.inputs.layout
    }

    /// The correspondence map of the head's fit at `size`² (made once per size and
    /// layout), `None` when the head reads the layers at its own UVs.
    pub fn correspondence(
        &mut self,
        size: u32,
        cancel: &CancelToken,
    ) -> Result<Option<Arc<Correspondence>>, Error> {
        let Some(fit) = self.inputs.layout.fit.clone() else {
            return Ok(None);
        };
        if let Some(c) = self.correspondences.iter().find(|c| c.size() == size) {
            return Ok(Some(c.clone()));
        }
        let c = Arc::new(Correspondence::new(&self.inputs.mesh, &fit, size, cancel)?);
        // The large map's and the transition texture's sizes: keep the last two.
        if self.correspondences.len() >= 2 {
            self.correspondences.remove(0);
        }
        self.correspondences.push(c.clone());
        Ok(Some(c))
    }

    /// Whether the project bakes any micro-relief at all ([`Project::micro_enabled`]).
    pub fn micro_enabled(&self) -> bool {
        self.project.micro_enabled()
    }

    /// The project's normal-map settings, wrapped at the edges when the last bake was
    /// tileable ([`BakeRequest::tileable`]).
    pub fn normal_settings(&self) -> NormalSettings {
        NormalSettings {
            strength: self.project.normal.strength,
            convention: self.project.normal.convention,
            tiling: self.tileable,
        }
    }

    /// Each vertex's template point (template metres): the fitted template's
    /// ([`crate::head::fit::Fit::template_point`]), the vertex itself on the built-in head (the
    /// template), none on a head read at its own UVs.
    pub fn template_points(&self) -> Vec<Option<glam::Vec3>> {
        let mesh = &self.inputs.mesh;
        match &self.inputs.layout.fit {
            Some(fit) => fit.template_point.clone(),
            None if self.project.mesh.path.is_none()
                && self.project.mesh.builtin == crate::project::BuiltinMesh::Head =>
            {
                let mpu = self.metres_per_unit();
                mesh.positions().iter().map(|p| Some(*p * mpu)).collect()
            }
            None => vec![None; mesh.vertex_count()],
        }
    }

    /// Each vertex's place on the template as the shape reads it: the fit's refined point
    /// ([`crate::head::fit::Fit::refined_point`], a smooth field's, which folds nowhere),
    /// its lower lip laid on the template's where it reaches further
    /// ([`crate::head::frame::Regions::with_lower_lip_as_template`]), else
    /// [`Scene::template_points`].
    pub fn shape_points(&self) -> Vec<Option<glam::Vec3>> {
        match &self.inputs.layout.fit {
            Some(fit) => {
                let lower = self.inputs.layout.lower_lip_reach;
                match crate::head::frame::Regions::template().filter(|_| lower > 0.0) {
                    Some(r) => (fit.refined_point.iter())
                        .map(|p| p.map(|p| r.with_lower_lip_as_template(p, lower)))
                        .collect(),
                    None => fit.refined_point.clone(),
                }
            }
            None => self.template_points(),
        }
    }
}

impl LargeMap {
    /// The heights in height units: −(the normalised map × `depth`, the project's
    /// `large.depth`), ≤ 0: the wrinkles cut in.
    pub fn scaled(&self, depth: f32) -> Result<HeightMap, Error> {
        scaled(&self.height, depth)
    }
}

#[cfg(test)]
mod face_only_tests;
#[cfg(test)]
mod heads_tests;
#[cfg(test)]
mod lips_tests;
#[cfg(test)]
mod micro_tests;
#[cfg(test)]
mod person_tests;
#[cfg(test)]
mod shape_tests;
#[cfg(test)]
mod tests;
