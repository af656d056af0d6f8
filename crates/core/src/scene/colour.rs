//! The scene's aged-colour stage ([`crate::layers::skin_colour`]): the surface per texel at a size,
//! the age spots of the head and the aged colour map, each kept while its inputs hold.

use std::sync::Arc;

use glam::Vec3;

use crate::age::ColourFactors;
use crate::base::arc_key::ArcKey;
use crate::base::cancel::CancelToken;
use crate::base::error::Error;
use crate::head::frame::Regions;
use crate::head::mesh::Mesh;
use crate::layers::skin_colour::{self, BaseColour, ColourSettings, Face, Spot, SurfaceTexels};
use crate::maps::mask::HeadImage;

/// What the surface and the spots are made from: the mesh, its fit and its units.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(super) struct HeadKey {
    pub mesh_generation: u64,
    pub layout_generation: u64,
    pub metres_per_unit: f32,
}

/// The texels' head, size and seed.
type TexelsKey = (HeadKey, u32, u64);

/// What a base colour is made from: the texels, the head's colour map, the skin colour.
type BaseKey = (TexelsKey, Option<Arc<HeadImage>>, [u32; 3]);

/// The spots' head, density (bits) and seed.
type SpotsKey = (HeadKey, u32, u64);

#[derive(Clone, Debug, Default)]
pub(super) struct ColourStage {
    texels: Option<(TexelsKey, Arc<SurfaceTexels>)>,
    spots: Option<(SpotsKey, Arc<Vec<Spot>>)>,
    /// The base colour of the texels (their key), the colour map (kept, so its address is
    /// not reused while it is compared) and the skin colour (bits).
    base: Option<(BaseKey, Arc<BaseColour>)>,
    image_key: Option<ImageKey>,
    pub image: Option<Arc<HeadImage>>,
}

/// What the painted hair was aged from: its ages (their identity), the age (bits), the bald and
/// hair colours (bits), the thinned shares (bits) and whether the pattern keeps the hairline.
type PaintedKey = (ArcKey<Vec<u8>>, u32, [u32; 3], [u32; 3], [u32; 2], bool);

#[derive(Clone, Debug, PartialEq)]
struct ImageKey {
    head: HeadKey,
    size: u32,
    base: Option<ArcKey<HeadImage>>,
    settings: ColourSettings,
    factors: ColourFactors,
    /// The painted hair's ([`PaintedKey`]).
    painted: Option<PaintedKey>,
}

/// The head as the stage reads it.
pub(super) struct Head<'a> {
    pub key: HeadKey,
    pub mesh: &'a Mesh,
    /// Each vertex's template point (template metres; [`super::Scene::template_point`]).
    pub template_point: &'a dyn Fn(usize) -> Option<Vec3>,
    pub base: Option<&'a Arc<HeadImage>>,
    /// The hair painted on the map ([`skin_colour::PaintedHair`]), when it has some.
    pub painted: Option<skin_colour::PaintedHair<'a>>,
    /// How much further down than the template's its lower lip's red reaches
    /// ([`super::HeadLayout::lower_lip_reach`]).
    pub lower_lip: f32,
    /// The identity of the painted hair's ages (their owner): the key of what was painted.
    pub painted_ages: Option<ArcKey<Vec<u8>>>,
}

impl ColourStage {
    /// The age factors of the last aged colour baked.
    pub fn factors(&self) -> Option<ColourFactors> {
        self.image_key.as_ref().map(|k| k.factors)
    }

    /// Bakes the aged colour at `size`², redoing only what changed; whether it changed.
    pub fn bake(
        &mut self,
        head: &Head,
        size: u32,
        settings: &ColourSettings,
        factors: &ColourFactors,
        cancel: &CancelToken,
    ) -> Result<bool, Error> {
        let key = ImageKey {
            head: head.key,
            size,
            base: head.base.map(ArcKey::of),
            settings: settings.clone(),
            factors: *factors,
            painted: head
                .painted
                .zip(head.painted_ages.clone())
                .map(|(p, ages)| {
                    (
                        ages,
                        p.t.to_bits(),
                        p.bald.to_array().map(f32::to_bits),
                        p.hair.to_array().map(f32::to_bits),
                        p.thinned.map(f32::to_bits),
                        p.keeps_hairline,
                    )
                }),
        };
        if self.image_key.as_ref() == Some(&key) && self.image.is_some() {
            return Ok(false);
        }
        let mpu = head.key.metres_per_unit;
        let template_point = head.template_point;
        let regions = Regions::template().ok_or_else(|| Error::InvalidValue {
            what: "the template's landmarks".into(),
            value: "incomplete".into(),
            expected: "eye and mouth corners, nose, chin and ears".into(),
        })?;
        let texels_key = (head.key, size, settings.seed);
        let texels = match &self.texels {
            Some((k, t)) if *k == texels_key => t.clone(),
            _ => {
                let t = Arc::new(SurfaceTexels::new(
                    head.mesh,
                    template_point,
                    mpu,
                    size,
                    Face {
                        regions,
                        drawn_crease: &crate::layers::shape::drawn_crease,
                        lower_lip: head.lower_lip,
                    },
                    settings.seed,
                    cancel,
                )?);
                self.texels = Some((texels_key, t.clone()));
                t
            }
        };
        let spots_key = (head.key, settings.spots_per_cm2.to_bits(), settings.seed);
        let spots = match &self.spots {
            Some((k, s)) if *k == spots_key => s.clone(),
            _ => {
                let s = Arc::new(skin_colour::place_spots(
                    head.mesh,
                    template_point,
                    mpu,
                    regions,
                    settings.spots_per_cm2,
                    settings.seed,
                ));
                self.spots = Some((spots_key, s.clone()));
                s
            }
        };
        let base_key: BaseKey = (
            texels_key,
            head.base.cloned(),
            settings.albedo.map(f32::to_bits),
        );
        let same = |k: &BaseKey| {
            k.0 == base_key.0
                && k.2 == base_key.2
                && match (&k.1, &base_key.1) {
                    (Some(a), Some(b)) => Arc::ptr_eq(a, b),
                    (None, None) => true,
                    _ => false,
                }
        };
        let base = match &self.base {
            Some((k, b)) if same(k) => b.clone(),
            _ => {
                cancel.check()?;
                let b = Arc::new(BaseColour::new(
                    head.base.map(|b| &**b),
                    settings.albedo,
                    &texels,
                ));
                self.base = Some((base_key, b.clone()));
                b
            }
        };
        let image = skin_colour::bake_from(
            &base,
            &texels,
            &spots,
            settings,
            factors,
            head.painted.as_ref(),
            cancel,
        )?;
        self.image = Some(Arc::new(image));
        self.image_key = Some(key);
        Ok(true)
    }

    /// The texels of the last bake.
    pub fn texels(&self) -> Option<&Arc<SurfaceTexels>> {
        self.texels.as_ref().map(|(_, t)| t)
    }

    /// The spots of the last bake.
    pub fn spots(&self) -> Option<&Arc<Vec<Spot>>> {
        self.spots.as_ref().map(|(_, s)| s)
    }
}
