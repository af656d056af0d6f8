//! A scene drawn by a headless renderer, age after age: `agesim render` and the renders
//! of an export. The same [`Layers`] and [`Uploaded`] as the editor's 3D view.

use agesim_core::base::cancel::CancelToken;
use agesim_core::project::Project;
use agesim_core::scene::{BakeRequest, Scene};
use agesim_render::{FrameParams, Renderer};

use super::{Layers, Uploaded};

/// A [`Scene`] baked at one map size at each age asked for, its layers uploaded to a
/// renderer as they change.
pub struct HeadlessView {
    scene: Scene,
    request: BakeRequest,
    layers: Layers,
    uploaded: Uploaded,
}

impl HeadlessView {
    /// `scene` baked with maps of `map_px` (and its hair when `hair`).
    pub fn new(scene: Scene, map_px: u32, hair: bool) -> Self {
        Self {
            scene,
            request: BakeRequest {
                large_size_px: map_px,
                micro_size_px: map_px,
                t: 0.0,
                // The renderer repeats the tiles over the head: they must wrap.
                tileable: true,
                fine: true,
                hair,
                packed: false,
                one_off: true,
                micro_normals: false,
                shape_relief: true,
            },
            layers: Layers::default(),
            uploaded: Uploaded::default(),
        }
    }

    pub fn scene(&self) -> &Scene {
        &self.scene
    }

    pub fn project(&self) -> &Project {
        self.scene.project()
    }

    /// Bakes the scene at age `t` and uploads to `renderer` what changed (everything, the
    /// first time).
    pub fn bake_and_upload(&mut self, renderer: &mut Renderer, t: f32) -> anyhow::Result<()> {
        self.request.t = t;
        let changed = self.scene.bake(&self.request, &CancelToken::never())?;
        let colour_px = self.scene.colour_px(self.request.large_size_px);
        self.scene
            .bake_colour(colour_px, t, &CancelToken::never())?;
        self.scene.prepare_shown_colour();
        self.scene.bake_shape(t);
        self.scene.bake_brows(t);
        self.layers.refresh(&self.scene, &changed, false);
        self.uploaded.upload(renderer, &self.layers)?;
        Ok(())
    }

    /// The frame of the project at age `t` through `camera` ([`super::frame_params`]).
    pub fn frame_params(&self, t: f32, camera: agesim_render::Camera) -> FrameParams {
        super::frame_params(self.scene.project(), self.layers.head(), t, camera)
    }
}
