//! The scene's hair: the transition texture and the hair instances of a bake, the brow and
//! lash hairs placed once per head and their strands at an age.

use super::*;

#[derive(Clone, Debug, PartialEq)]
pub(super) struct HairKey {
    mesh_generation: u64,
    transition_generation: u64,
    density: f32,
    metres_per_unit: f32,
    seed: u64,
    deviation_deg: f32,
    onset_t: (f32, f32),
    thinning: f32,
    loss: crate::layers::hair::HairLoss,
    taper_mm: f32,
}

/// What brow hairs are placed from: mesh and layout generations, metres per unit (bits),
/// seed.
pub(super) type BrowHairsKey = (u64, u64, u32, u64);

/// The hairs around the eyes, placed once per head: the brows and the upper lids' lashes.
#[derive(Debug)]
pub(super) struct EyeHairs {
    brows: crate::layers::hair::brows::BrowHairs,
    pub(crate) lashes: crate::layers::hair::lashes::Lashes,
}

impl EyeHairs {
    fn is_empty(&self) -> bool {
        self.brows.is_empty() && self.lashes.is_empty()
    }
}

/// What the hair's transition texture was made from: the hair masks, the metric (its
/// name), the size and the layout generation.
pub(super) type TransitionKey = (ArcKey<(Mask, Mask)>, String, Option<u32>, u64);

/// What the brow strands of an age are made from: the brow hairs and the shape (their
/// identities), the brows' gray fraction and growth (bits), and the loss pattern.
pub(super) type BrowsKey = (
    ArcKey<EyeHairs>,
    Option<ArcKey<AgedShape>>,
    u32,
    u32,
    crate::layers::hair::HairLoss,
);

impl Scene {
    pub(super) fn bake_hair(&mut self, cancel: &CancelToken) -> Result<Changed, Error> {
        let mut changed = Changed::default();
        let h = &self.project.hair.clone();
        let Some(masks) = self.inputs.hair_masks.clone() else {
            return Ok(changed);
        };
        // A face only has no scalp to grow hair on (the layout says so).
        if self.inputs.layout.face_only {
            if self.hair.take().is_some() {
                self.hair_key = None;
                changed.hair = true;
            }
            return Ok(changed);
        }
        let tkey = (
            ArcKey::of(&masks),
            format!("{:?}", h.metric),
            h.transition_size_px,
            self.layout_generation,
        );
        if self.transition_key.as_ref() != Some(&tkey) || self.transition.is_none() {
            cancel.check()?;
            let (outer, inner) = &*masks;
            // An all-black outer mask means no hair at age 0; it is almost surely the
            // wrong file, and would leave only the inner region's hair: say so.
            if outer
                .values()
                .iter()
                .all(|&v| v < crate::layers::hair::transition::REGION_THRESHOLD)
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
            let size = transition_size(h.transition_size_px, outer, inner, self.udim_grid());
            // The built-in masks come with the order their hair goes in; masks of the
            // artist's own grow their transition from the inner region.
            let order = (h.outer_mask.is_none() && h.inner_mask.is_none())
                .then(crate::defaults::hair_order_mask)
                .flatten();
            let build = |o: &Mask, i: &Mask, order: Option<&Mask>| match order {
                Some(order) => TransitionTexture::from_order(o, i, order, size, size),
                None => TransitionTexture::from_masks(o, i, size, size, h.metric),
            };
            // A fitted head: the masks read through the correspondence, in its own layout.
            let t = match self.correspondence(size, cancel)? {
                Some(c) => {
                    let through = |m: &Mask| {
                        let values = c.resample(m.values(), m.width_px(), m.height_px());
                        Mask::from_values(size, size, values)
                    };
                    let (o, i) = (through(outer)?, through(inner)?);
                    let order = order.map(through).transpose()?;
                    build(&o, &i, order.as_ref())?
                }
                None => build(outer, inner, order)?,
            };
            self.transition = Some(Arc::new(t));
            self.transition_key = Some(tkey);
            self.transition_generation += 1;
            changed.transition = true;
        }
        let delay = self.measure_person(cancel)?.graying_delay_years;
        let key = HairKey {
            mesh_generation: self.mesh_generation,
            transition_generation: self.transition_generation,
            density: h.density_per_cm2,
            metres_per_unit: self.metres_per_unit(),
            seed: h.seed,
            deviation_deg: h.max_deviation_deg,
            onset_t: self.project.graying_onset_t(delay),
            thinning: h.thinning,
            loss: self.hair_loss().loss,
            taper_mm: h.taper_mm,
        };
        if self.hair_key.as_ref() == Some(&key) && self.hair.is_some() {
            return Ok(changed);
        }
        cancel.check()?;
        let Some(transition) = &self.transition else {
            return Ok(changed);
        };
        let params = HairParams::new(h.density_per_cm2, self.metres_per_unit())?
            .with_seed(h.seed)
            .with_max_deviation_rad(h.max_deviation_deg.to_radians())?
            .with_graying_onset_range(key.onset_t.0, key.onset_t.1)?
            .with_thinning(h.thinning, crate::layers::hair::RECESSION_SPREAD)?
            .with_taper_mm(h.taper_mm)?
            .with_loss(key.loss);
        let mesh = &self.inputs.mesh;
        // Hair grows on the skin, not on eyes, teeth or lashes that come with the head.
        let skin = mesh.skin_indices();
        let surface = SurfaceRef::new(mesh.positions(), mesh.normals(), mesh.uvs(), &skin)?;
        let hair = HairInstances::generate(&surface, transition, &params)?;
        self.hair = Some(Arc::new(hair));
        self.hair_key = Some(key);
        changed.hair = true;
        Ok(changed)
    }

    /// Makes the brow hairs at age `t` (docs/models.md §9 "Eyebrows": their curves on the
    /// shape of the last [`Scene::bake_shape`], their gray; [`Scene::aged_brows`]). None
    /// when the hair or the brows are off, or on a head read at its own UVs (no fit: no
    /// brow on it). Redone only when something they are made from changed; returns
    /// whether it was.
    pub fn bake_brows(&mut self, t: f32) -> bool {
        let h = &self.project.hair;
        let hairs = if h.enabled && h.brows {
            self.brow_hairs()
        } else {
            None
        };
        let Some(hairs) = hairs else {
            let changed = self.brows_aged.is_some();
            self.brows_aged = None;
            return changed;
        };
        let factors = self.colour_factors(t);
        let shape = self.aged_shape().cloned();
        let key = (
            ArcKey::of(&hairs),
            shape.as_ref().map(ArcKey::of),
            factors.brow_gray_fraction().to_bits(),
            factors.contrast.to_bits(),
            self.hair_loss().loss,
        );
        if self.brows_aged.as_ref().is_some_and(|(k, _)| *k == key) {
            return false;
        }
        let shape = shape
            .as_deref()
            .map(|s| (s.delta.as_slice(), s.normals.as_slice()));
        // The brows age as the hair loss's pattern: a woman's thin, a man's grow bushy.
        let female = self.hair_loss().loss == crate::layers::hair::HairLoss::Female;
        let mut strands = hairs
            .brows
            .strands(&self.inputs.mesh, &factors, shape, female);
        strands.extend(hairs.lashes.strands(&self.inputs.mesh, &factors, shape));
        self.brows_aged = Some((key, Arc::new(strands)));
        true
    }

    /// The brow strands and then the lashes of the last [`Scene::bake_brows`].
    pub fn aged_brows(&self) -> Option<&Arc<Vec<crate::layers::hair::brows::BrowStrand>>> {
        self.brows_aged.as_ref().map(|(_, b)| b)
    }

    /// The brow hairs and lashes on this head, placed once per head and seed; `None` when
    /// it has no template points (a head read at its own UVs) or none land on a brow or a
    /// lid.
    pub(super) fn brow_hairs(&mut self) -> Option<Arc<EyeHairs>> {
        let key = (
            self.mesh_generation,
            self.layout_generation,
            self.metres_per_unit().to_bits(),
            self.project.hair.seed,
        );
        if let Some((k, b)) = &self.brows
            && *k == key
        {
            return (!b.is_empty()).then(|| b.clone());
        }
        let regions = crate::head::frame::Regions::template()?;
        let points = self.template_points();
        let point = |v: usize| points.get(v).copied().flatten();
        let (mesh, metres_per_unit) = (&self.inputs.mesh, self.metres_per_unit());
        let hairs = Arc::new(EyeHairs {
            brows: crate::layers::hair::brows::BrowHairs::generate(
                mesh,
                &point,
                regions,
                metres_per_unit,
                key.3,
            ),
            lashes: crate::layers::hair::lashes::Lashes::generate(
                mesh,
                &point,
                regions,
                metres_per_unit,
                key.3,
                mesh.parts()
                    .iter()
                    .any(crate::layers::skin_colour::is_eyeball),
            ),
        });
        self.brows = Some((key, hairs.clone()));
        (!hairs.is_empty()).then_some(hairs)
    }
}

/// The transition texture's side: `hair.transition_size_px`, else the masks' larger side;
/// per tile of a UDIM head, whose transition is its atlas of `grid` × `grid` tiles (at
/// most [`MAX_TRANSITION_PX`] per side).
pub(super) fn transition_size(set: Option<u32>, outer: &Mask, inner: &Mask, grid: u32) -> u32 {
    let tile = set.unwrap_or_else(|| {
        outer
            .width_px()
            .max(outer.height_px())
            .max(inner.width_px())
            .max(inner.height_px())
    });
    let grid = grid.max(1);
    // Capped, a whole number of texels a tile, so each tile's file is its cell exactly.
    let cap = (MAX_TRANSITION_PX / grid * grid).max(tile);
    tile.saturating_mul(grid).min(cap)
}

/// The largest side of a UDIM head's transition atlas (its tiles smaller beyond it).
pub const MAX_TRANSITION_PX: u32 = 8192;
