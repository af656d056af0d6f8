//! A bake of the scene: the request's layers at its sizes and age, each redone only when
//! its inputs changed ([`Changed`] says which).

use super::*;

pub(super) type FineWrinkleSettingsKey = (Option<PathBuf>, u32, u32, f32, f32, f32, f32, u64);

/// h −= l × depth, pixel by pixel: the large wrinkles cut into the skin.
pub(super) fn add_into(height: &mut HeightMap, large: &HeightMap, depth: f32) {
    for (h, l) in height.data_mut().iter_mut().zip(large.data()) {
        *h -= l * depth;
    }
}

/// −`map` × `depth`: a normalised large-wrinkle map (1 = the deepest point of a full-depth
/// wrinkle) as heights in height units, ≤ 0: wrinkles are cut into the skin
/// (docs/models.md §2 "Heights").
pub(super) fn scaled(map: &HeightMap, depth: f32) -> Result<HeightMap, Error> {
    let data = map.data().iter().map(|h| -h * depth).collect();
    HeightMap::from_vec(map.width_px(), map.height_px(), data)
}

impl Scene {
    /// Bakes what `request` asks for at its age, redoing only what changed since the last
    /// bake. On error (or cancellation) every kept output stays as it was.
    pub fn bake(&mut self, request: &BakeRequest, cancel: &CancelToken) -> Result<Changed, Error> {
        crate::maps::heightmap::check_size(request.large_size_px, request.micro_size_px)?;
        // The person's own colours first: the hair and the colour gray by them.
        self.own_colours(cancel)?;
        self.weigh_micro()?;
        let (fibres, curves) = self.fibres();
        self.factors = self.project.age.factors(request.t, &curves);
        let mut changed = Changed::default();
        let normal = NormalSettings {
            tiling: request.tileable,
            ..self.normal_settings()
        };
        let micro_enabled = self.micro_enabled();
        let correspondence = if self.project.large.enabled {
            self.correspondence(request.large_size_px, cancel)?
        } else {
            None
        };
        let fibres = self.laid_on_surface(fibres, correspondence.is_some());
        let relief = match &correspondence {
            _ if !self.project.large.enabled || !request.shape_relief => None,
            Some(c) => self.shape_relief(c.size(), cancel)?,
            None => self.shape_relief(request.large_size_px, cancel)?,
        };
        let years = self.project.age.mapping().years(request.t);
        let shape_factors = self.shape_relief_factors(years);
        // The relief depth of the default view and wrinkle depth: the relief has its
        // millimetres there, and deepens with the wrinkles when either is turned up (a
        // slider that redraws without a bake stays so).
        // Drawn deeper in old age (the wrinkles' depth gain), the map's relief is shallower
        // by as much, so it keeps its millimetres.
        let depth_uv = crate::project::ViewSection::default().disp_scale
            * crate::project::LargeSection::default().depth
            * crate::age::wrinkle_depth_gain(years)
            * self.relief_scale();
        let relief_at = relief.as_ref().map(|relief| large::ReliefAt {
            relief,
            factors: &shape_factors,
            depth_uv,
        });
        let layout_generation = self.layout_generation;
        let (large, micro) = (&mut self.large, &mut self.micro);
        let (project, inputs, factors) = (&self.project, &self.inputs, &self.factors);
        // The micro-relief follows the request's tiling, not the document's `tile`.
        let tiled;
        let micro_project = if project.tile == request.tileable {
            project
        } else {
            tiled = Project {
                tile: request.tileable,
                ..project.clone()
            };
            &tiled
        };
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
                    let layout = large::HeadLayoutMap {
                        correspondence: correspondence.as_deref(),
                        generation: layout_generation,
                    };
                    large.bake(
                        project, &fibres, factors, mask, layout, request, &normal, relief_at,
                        cancel,
                    )
                } else {
                    Ok(large.clear())
                }
            },
            || {
                if micro_enabled {
                    micro.bake(micro_project, factors, request, &normal, cancel)
                } else {
                    Ok(micro.clear())
                }
            },
        );
        changed.merge(large_result?);
        changed.merge(micro_result?);
        // The kept maps are now this request's (a failed bake keeps the last one's).
        self.tileable = request.tileable;
        if request.fine && self.project.fine.enabled {
            changed.merge(self.bake_fine(cancel)?);
        }
        if request.hair && self.project.hair.enabled {
            changed.merge(self.bake_hair(cancel)?);
        }
        Ok(changed)
    }

    pub(super) fn bake_fine(&mut self, cancel: &CancelToken) -> Result<Changed, Error> {
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
}
