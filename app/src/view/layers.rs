//! The renderer's inputs of one bake ([`Layers`]), prepared off the drawing thread, and
//! what a renderer holds of them ([`Uploaded`]): a layer is uploaded when it is not the
//! allocation the renderer was given last.

use std::sync::Arc;

use super::HeadScale;
use agesim_core::base::arc_key::AnyKey;
use agesim_core::layers::hair::HairInstances;
use agesim_core::maps::mask::HeadImage;
use agesim_core::scene::{Changed, Scene};
use agesim_core::{HeightMap, Mesh};
use agesim_render::{PreparedLayer, RenderError, Renderer, ShapeUpload, TileLayer, Upload, ViewId};

/// Every uploaded input of the renderer, each shared: a layer that a bake did not change
/// is the same allocation as before, so its address says whether to upload it again.
#[derive(Clone, Debug)]
pub struct Layers {
    pub mesh: Option<Arc<Mesh>>,
    /// The large-wrinkle map, normalised (a full-depth wrinkle spans 1), as f16;
    /// `None` when the layer is off (the renderer then draws flat skin).
    pub large: Option<Arc<PreparedLayer>>,
    /// The micro-relief tile and the fine-wrinkle tile, as f16 with mip levels.
    pub micro: Option<Arc<PreparedLayer>>,
    pub fine: Option<Arc<PreparedLayer>>,
    pub hair: Option<Arc<HairInstances>>,
    /// How long a mesh unit is, metres ([`Scene::metres_per_unit`]).
    pub metres_per_unit: f32,
    /// The head's relief depth per template UV unit ([`Scene::relief_scale`]).
    pub relief_scale: f32,
    /// The head's UV density over its face ([`Scene::surface_scale`]).
    pub surface_scale: Option<agesim_core::head::mesh::SurfaceScale>,
    /// The head's base colour map ([`Scene::colour_map`]).
    pub colour: Option<Arc<HeadImage>>,
    /// The aged base colour of this bake's age ([`Scene::aged_colour`]): shown instead of
    /// `colour`, per view (the compare view has its own age's).
    pub aged: Option<Arc<HeadImage>>,
    /// The shape of this bake's age ([`Scene::aged_shape`]), per view like the colour.
    pub shape: Option<Arc<agesim_core::scene::AgedShape>>,
    /// The brow hairs of this bake's age ([`Scene::aged_brows`]), per view.
    pub brows: Option<Arc<Vec<agesim_core::layers::hair::brows::BrowStrand>>>,
    /// The head's normal map ([`Scene::normal_map`]).
    pub normal: Option<Arc<HeadImage>>,
    /// Where the micro-relief lies ([`Scene::micro_weight`]).
    pub micro_weight: Option<Arc<HeadImage>>,
    /// The person's hair and brows ([`Scene::person`]).
    pub person: Option<agesim_core::scene::Person>,
}

impl Default for Layers {
    /// No layer yet, in metres.
    fn default() -> Self {
        Self {
            mesh: None,
            large: None,
            micro: None,
            fine: None,
            hair: None,
            metres_per_unit: 1.0,
            relief_scale: 1.0,
            surface_scale: None,
            colour: None,
            aged: None,
            shape: None,
            brows: None,
            person: None,
            normal: None,
            micro_weight: None,
        }
    }
}

impl Layers {
    /// Takes from `scene` what its last bake changed (everything when `all`: these layers
    /// were filled from another scene).
    pub fn refresh(&mut self, scene: &Scene, changed: &Changed, all: bool) {
        let new_mesh = all || changed.mesh || self.mesh.is_none();
        if new_mesh {
            self.mesh = Some(scene.mesh().clone());
        }
        if all || changed.large || (self.large.is_none() && scene.large().is_some()) {
            self.large = scene
                .large()
                .map(|l| Arc::new(PreparedLayer::large_wrinkles(&l.height)));
        }
        if all || changed.micro || (self.micro.is_none() && scene.micro().is_some()) {
            self.micro = scene
                .micro()
                .map(|m| Arc::new(PreparedLayer::tile(&m.height)));
        }
        if all || changed.fine || (self.fine.is_none() && scene.fine().is_some()) {
            self.fine = scene.fine().map(|f| Arc::new(PreparedLayer::tile(f)));
        }
        self.hair = scene.hair().cloned();
        self.colour = scene.colour_map().cloned();
        // The view shows the aged colour with the hair's ages in its alpha (the scalp's
        // tint); exports take `Scene::aged_colour` itself.
        self.aged = scene.shown_colour().cloned();
        self.shape = scene.aged_shape().cloned();
        self.brows = scene.aged_brows().cloned();
        self.normal = scene.normal_map().cloned();
        self.micro_weight = scene.micro_weight().cloned();
        self.person = Some(scene.person());
        let metres_per_unit = scene.metres_per_unit();
        // Measured over the mesh: only when the mesh or its units change.
        if new_mesh || metres_per_unit != self.metres_per_unit {
            self.relief_scale = scene.relief_scale();
            self.surface_scale = scene.surface_scale();
        }
        self.metres_per_unit = metres_per_unit;
    }

    /// The head's scale for [`super::frame_params`].
    pub fn head(&self) -> HeadScale {
        HeadScale {
            metres_per_unit: self.metres_per_unit,
            relief_scale: self.relief_scale,
            person: self.person,
        }
    }
}

/// A head picture as the renderer takes it.
fn picture(p: &Option<Arc<HeadImage>>) -> Option<(u32, u32, &[u8])> {
    p.as_deref()
        .map(|c| (c.width_px, c.height_px, c.rgba.as_slice()))
}

/// The identity of a shared layer (`None`: none). An `AnyKey`, not the allocation's
/// address: a new layer allocated where a dropped one was is not taken for it.
fn stamp<T: std::any::Any + Send + Sync>(a: &Option<Arc<T>>) -> Stamp {
    a.as_ref().map(AnyKey::of_any)
}

/// See [`stamp`].
type Stamp = Option<AnyKey>;

/// Whether `key` names the layer `a` (both none counts), without making a key.
fn same<T: std::any::Any + Send + Sync>(key: &Stamp, a: &Option<Arc<T>>) -> bool {
    match (key, a) {
        (Some(k), Some(a)) => k.is_any(a),
        (None, None) => true,
        _ => false,
    }
}

/// What one renderer was last given, by identity: compare two to know whether a frame
/// drawn since shows the current layers.
#[derive(Clone, Debug, Default, PartialEq, Eq)]
pub struct Uploaded {
    /// The mesh and the metres per unit it was uploaded with (its bits).
    mesh: (Stamp, u32),
    large: Stamp,
    micro: Stamp,
    fine: Stamp,
    hair: Stamp,
    colour: Stamp,
    aged: Stamp,
    shape: Stamp,
    brows: Stamp,
    normal: Stamp,
    micro_weight: Stamp,
}

impl Uploaded {
    /// Uploads to `renderer` every layer of `layers` it does not hold yet. A layer whose
    /// upload failed is not tried again until it changes; the first error is returned.
    pub fn upload(&mut self, renderer: &mut Renderer, layers: &Layers) -> Result<(), RenderError> {
        let metres_per_unit = layers.metres_per_unit;
        let mut result = Ok(());
        let bits = metres_per_unit.to_bits();
        if !(same(&self.mesh.0, &layers.mesh) && self.mesh.1 == bits)
            && let Some(m) = &layers.mesh
        {
            result = result.and(renderer.upload_mesh(m, metres_per_unit));
            if let Some(scale) = layers.surface_scale {
                renderer.set_surface_scale(scale);
            }
            self.mesh = (stamp(&layers.mesh), bits);
        }
        result = result.and(self.upload_age_layers(renderer, ViewId::MAIN, layers));
        if !same(&self.fine, &layers.fine)
            && let Some(fine) = &layers.fine
        {
            let tile = Upload::Tile {
                layer: TileLayer::Fine,
                tile: fine,
            };
            result = result.and(renderer.upload_prepared(&tile));
            self.fine = stamp(&layers.fine);
        }
        if !same(&self.hair, &layers.hair)
            && let Some(h) = &layers.hair
        {
            renderer.upload_hair(h);
            self.hair = stamp(&layers.hair);
        }
        if !same(&self.colour, &layers.colour) {
            result = result.and(renderer.upload_colour_map(picture(&layers.colour)));
            self.colour = stamp(&layers.colour);
        }
        if !same(&self.normal, &layers.normal) {
            result = result.and(renderer.upload_normal_map(picture(&layers.normal)));
            self.normal = stamp(&layers.normal);
        }
        if !same(&self.micro_weight, &layers.micro_weight) {
            result = result.and(renderer.upload_micro_weight(picture(&layers.micro_weight)));
            self.micro_weight = stamp(&layers.micro_weight);
        }
        result
    }

    /// Uploads the layers that differ between two ages (the large-wrinkle map, the
    /// micro-relief tile, the aged colour, the shape, the brows) to `view` of `renderer`: a second view (the compare age) shares
    /// the mesh, the fine tile and the hair of the first.
    pub fn upload_age_layers(
        &mut self,
        renderer: &mut Renderer,
        view: ViewId,
        layers: &Layers,
    ) -> Result<(), RenderError> {
        let mut result = Ok(());
        if !same(&self.large, &layers.large) {
            result = result.and(match &layers.large {
                Some(large) => renderer.upload_prepared_to(view, &Upload::LargeWrinkles(large)),
                // The layer is off: flat skin (height 1 = the polygon), not the last map.
                None => {
                    let flat =
                        PreparedLayer::large_wrinkles(&HeightMap::from_vec(1, 1, vec![1.0])?);
                    renderer.upload_prepared_to(view, &Upload::LargeWrinkles(&flat))
                }
            });
            self.large = stamp(&layers.large);
        }
        if !same(&self.shape, &layers.shape) {
            let shape = layers.shape.as_deref().map(|s| ShapeUpload {
                delta: &s.delta,
                normals: &s.normals,
                hollow_mm: &s.hollow_mm,
                occlusion: &s.occlusion,
            });
            result = result.and(renderer.upload_shape_to(view, shape));
            self.shape = stamp(&layers.shape);
        }
        if !same(&self.brows, &layers.brows) {
            result = result
                .and(renderer.upload_brows_to(view, layers.brows.as_deref().map(Vec::as_slice)));
            self.brows = stamp(&layers.brows);
        }
        if !same(&self.aged, &layers.aged) {
            result = result.and(renderer.upload_colour_map_to(view, picture(&layers.aged)));
            self.aged = stamp(&layers.aged);
        }
        // A micro tile that is off stays uploaded: the frame turns the layer off
        // (`SkinParams::micro_relief`).
        if !same(&self.micro, &layers.micro)
            && let Some(micro) = &layers.micro
        {
            let tile = Upload::Tile {
                layer: TileLayer::Micro,
                tile: micro,
            };
            result = result.and(renderer.upload_prepared_to(view, &tile));
            self.micro = stamp(&layers.micro);
        }
        result
    }
}
