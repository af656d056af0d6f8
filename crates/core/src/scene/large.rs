//! The large-wrinkle stage of a scene: the fibre stamps, the map at an age and its
//! packing, each kept with the key it was made from.

use std::sync::Arc;

use super::{BakeRequest, Changed, LargeMap, scaled};
use crate::age::AgeFactors;
use crate::base::arc_key::ArcKey;
use crate::base::cancel::CancelToken;
use crate::base::error::Error;
use crate::head::fit::Correspondence;
use crate::layers::shape::relief::ShapeRelief;
use crate::layers::wrinkles::large_layer::LargeLayer;
use crate::layers::wrinkles::muscle::{Fibre, MaskValues};
use crate::maps::heightmap::HeightMap;
use crate::maps::mask::Mask;
use crate::maps::normal_map::{self, NormalSettings};
use crate::project::Project;

/// The keys each kept output was made from (see the module table).
#[derive(Clone, Debug, Default, PartialEq)]
pub(super) struct LargeKey {
    layer_fibres: Vec<Fibre>,
    size: u32,
    factors: Vec<f32>,
    gamma: f32,
    /// The depth and normal settings of the packing (only when packed: the map itself is
    /// normalised).
    packed_depth: Option<f32>,
    mask_generation: u64,
    normal: Option<NormalSettings>,
    packed: bool,
    /// The head layout's generation, when read through a correspondence.
    layout: Option<(u64, u32)>,
    /// The shape's relief added to it: its identity, the regions' factors and the relief
    /// depth (bits).
    relief: Option<(ArcKey<ShapeRelief>, Vec<u32>, u32)>,
}

/// The shape's relief finer than the head's triangles ([`crate::layers::shape::relief`]) at an
/// age: added to the map in the head's layout.
#[derive(Clone, Copy)]
pub(super) struct ReliefAt<'a> {
    pub(super) relief: &'a std::sync::Arc<ShapeRelief>,
    /// The regions' curves at the age, in [`crate::layers::shape::REGIONS`] order.
    pub(super) factors: &'a [f32],
    /// The depth of a normalised height of 1, UV units (the default view's relief depth).
    pub(super) depth_uv: f32,
}

/// The large-wrinkle stage: fibre stamps, the map at an age, its packing.
#[derive(Clone, Debug, Default)]
pub(super) struct LargeStage {
    layer: LargeLayer,
    pub(super) key: Option<LargeKey>,
    pub(super) map: Option<LargeMap>,
    /// The previous map's buffer, baked into next (no allocation, no page faults).
    spare: Option<HeightMap>,
    /// The mask sampled at the map's pixel centres: (mask generation, size, values).
    mask_samples: Option<(u64, u32, Arc<Vec<f32>>)>,
}

/// The correspondence a fitted head reads the template's map through, and the layout
/// generation that identifies it.
#[derive(Clone, Copy)]
pub(super) struct HeadLayoutMap<'a> {
    pub(super) correspondence: Option<&'a Correspondence>,
    pub(super) generation: u64,
}

/// The large-wrinkle mask and the generation that identifies it.
#[derive(Clone, Copy)]
pub(super) struct LargeMask<'a> {
    pub(super) mask: Option<&'a Mask>,
    pub(super) generation: u64,
}

impl LargeStage {
    /// Drops the map (the layer is off).
    pub(super) fn clear(&mut self) -> Changed {
        self.key = None;
        Changed {
            large: self.map.take().is_some(),
            ..Changed::default()
        }
    }

    #[allow(clippy::too_many_arguments)]
    pub(super) fn bake(
        &mut self,
        p: &Project,
        fibres: &[Fibre],
        factors: &AgeFactors,
        large_mask: LargeMask<'_>,
        layout: HeadLayoutMap<'_>,
        request: &BakeRequest,
        normal: &NormalSettings,
        relief: Option<ReliefAt<'_>>,
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
            packed_depth: request.packed.then_some(p.large_depth_at(factors.years)),
            mask_generation: large_mask.generation,
            normal: request.packed.then_some(*normal),
            packed: request.packed,
            layout: layout.correspondence.map(|c| (layout.generation, c.size())),
            relief: relief.map(|r| {
                (
                    ArcKey::of(r.relief),
                    r.factors.iter().map(|f| f.to_bits()).collect(),
                    r.depth_uv.to_bits(),
                )
            }),
        };
        if self.key.as_ref() == Some(&key) && self.map.is_some() {
            return Ok(changed);
        }
        // A one-off bake samples the mask from its taps (no map-sized buffer kept); the
        // editor's bakes keep the samples for the next change.
        let columns = match (request.one_off, large_mask.mask) {
            (true, Some(m)) => crate::layers::wrinkles::muscle::mask_columns(m, size),
            _ => Vec::new(),
        };
        let mask_samples = match (large_mask.mask, &self.mask_samples) {
            (None, _) => None,
            _ if request.one_off => None,
            (Some(_), Some((g, s, v))) if *g == large_mask.generation && *s == size => {
                Some(v.clone())
            }
            (Some(mask), _) => {
                let v = Arc::new(crate::layers::wrinkles::muscle::sample_mask(
                    mask, size, size,
                ));
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
            crate::layers::wrinkles::large_layer::bake_direct(
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
        self.keep(
            height,
            layout,
            (p.large_depth_at(factors.years), factors.years),
            request,
            normal,
            relief,
            key,
            cancel,
        )?;
        changed.large = true;
        Ok(changed)
    }

    /// Packs a finished (normalised) map if asked, scaled by the depth, reads it into the
    /// head's layout through the correspondence (a fitted head), adds the shape's relief
    /// there (the packed map, the wrinkles' own, has none), and keeps it.
    #[allow(clippy::too_many_arguments)]
    fn keep(
        &mut self,
        height: HeightMap,
        layout: HeadLayoutMap<'_>,
        (depth, years): (f32, f32),
        request: &BakeRequest,
        normal: &NormalSettings,
        relief: Option<ReliefAt<'_>>,
        key: LargeKey,
        cancel: &CancelToken,
    ) -> Result<(), Error> {
        let packed_range = (-depth.max(f32::MIN_POSITIVE), 0.0);
        let packed_rgba = if request.packed {
            normal_map::pack_rgba8(&scaled(&height, depth)?, normal, packed_range)?
        } else {
            Vec::new()
        };
        cancel.check()?;
        let (mut height, template) = match layout.correspondence {
            Some(c) => {
                let (w, h) = (height.width_px(), height.height_px());
                let head =
                    HeightMap::from_vec(c.size(), c.size(), c.resample(height.data(), w, h))?;
                (head, Some(height))
            }
            None => (height, None),
        };
        if let Some(r) = relief {
            r.relief.apply(&mut height, r.factors, r.depth_uv);
        }
        cancel.check()?;
        let previous = self.map.replace(LargeMap {
            height,
            years,
            template,
            packed_rgba,
            packed_range,
        });
        // The buffer the next bake fills: the template-layout one when there is one.
        self.spare = previous.map(|l| l.template.unwrap_or(l.height));
        self.key = Some(key);
        Ok(())
    }
}
