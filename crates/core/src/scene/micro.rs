//! The micro-relief stage of a scene: the features (pores, furrows) and the tile at an
//! age, its features and its noise kept apart for small tiles.

use super::{BakeRequest, Changed, MicroTile};
use crate::age::AgeFactors;
use crate::base::cancel::CancelToken;
use crate::base::error::Error;
use crate::layers::micro::MicroRelief;
use crate::maps::heightmap::HeightMap;
use crate::maps::normal_map::{self, NormalSettings};
use crate::project::Project;

/// Tiles up to this side keep their features and their noise as separate maps (the
/// editor's preview and full tiles), so an age change re-bakes only the features and a
/// noise change only the noise; larger tiles (one-off exports) bake in one fused pass.
const SPLIT_MAX_PX: u32 = 1024;

/// The micro-relief stage: features and the tile at an age.
#[derive(Clone, Debug, Default)]
pub(super) struct MicroStage {
    pub(super) relief: Option<MicroRelief>,
    pub(super) key: Option<MicroKey>,
    pub(super) tile: Option<MicroTile>,
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
    pub(super) fn clear(&mut self) -> Changed {
        self.key = None;
        Changed {
            micro: self.tile.take().is_some(),
            ..Changed::default()
        }
    }

    pub(super) fn bake(
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
        age_relief(&mut relief, project, factors);
        let scales = relief.age_scales();
        let directions = relief.age_directions();
        let key = MicroKey {
            project: micro_relevant(project),
            scales,
            directions,
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
                normal_rgb: crate::maps::heightmap::zeroed_vec(
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
        use crate::layers::micro::bake::Parts;
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
                    crate::base::simd::Level::detect(),
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

#[derive(Clone, Debug, PartialEq)]
pub(super) struct MicroKey {
    project: Project,
    scales: (f32, f32),
    directions: (f32, f32),
    size: u32,
    normals: bool,
}

/// Sets the age of `relief` (`docs/models.md` "Age"): its pores' radius and furrows' depth
/// scales, and how its pores stretch and furrows align along the tension lines (the
/// `pores.elongation` and `furrows.anisotropy` at full age, with the furrows' curve).
pub(crate) fn age_relief(relief: &mut MicroRelief, project: &Project, factors: &AgeFactors) {
    relief.set_age_scales(factors.pore_radius_scale, factors.furrow_depth_scale);
    let along = project.age.furrows.factor(factors.years);
    relief.set_age_directions(
        1.0 + (project.pores.elongation - 1.0) * along,
        project.furrows.anisotropy * along,
    );
}

/// What the micro-relief's weight map is made from: the mesh and layout generations.
pub(super) type MicroWeightKey = (u64, u64);

/// The side of the micro-relief's weight map ([`Scene::micro_weight`]).
pub const MICRO_WEIGHT_PX: u32 = 1024;

impl super::Scene {
    /// Where the micro-relief lies on this head (docs/models.md §4 "Where on the head"):
    /// its weight over the head's UVs ([`crate::layers::micro::weight::map`] of each
    /// skin vertex's [`crate::layers::micro::weight::lips_at`], the lower lip reaching
    /// as far as this head's: [`super::HeadLayout::lower_lip_reach`]), `MICRO_WEIGHT_PX`²;
    /// `None` when it is everywhere the whole tile (a head off the template). Made by
    /// [`super::Scene::bake`].
    pub fn micro_weight(&self) -> Option<&std::sync::Arc<crate::maps::mask::HeadImage>> {
        self.micro_weight.as_ref().and_then(|(_, m)| m.as_ref())
    }

    /// Makes [`super::Scene::micro_weight`] once per mesh and layout.
    pub(super) fn weigh_micro(&mut self) -> Result<(), Error> {
        let key = (self.mesh_generation, self.layout_generation);
        if self.micro_weight.as_ref().is_some_and(|(k, _)| *k == key) {
            return Ok(());
        }
        let map = match crate::head::frame::Regions::template() {
            Some(regions) => {
                let lower = self.inputs.layout.lower_lip_reach;
                let lips: Vec<f32> = self
                    .template_points()
                    .into_iter()
                    .map(|t| crate::layers::micro::weight::lips_at(regions, t, lower))
                    .collect();
                if lips.iter().all(|&l| l <= 0.0) {
                    None
                } else {
                    let mesh = &self.inputs.mesh;
                    Some(std::sync::Arc::new(crate::layers::micro::weight::map(
                        mesh.uvs(),
                        &mesh.skin_indices(),
                        &lips,
                        MICRO_WEIGHT_PX,
                    )?))
                }
            }
            None => None,
        };
        self.micro_weight = Some((key, map));
        Ok(())
    }
}
