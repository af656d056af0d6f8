//! The aged colour of the scene at an age, and the 3D view's colour map: the aged colour
//! with the hair's age at each texel in its alpha (`layers::hair::scalp`).

use super::*;
use crate::maps::mask::HeadImage;

/// The transition generation, and the width and height of a kept hair-age alpha.
pub(super) type HairAlphaKey = (u64, u32, u32);

/// What the blank eyeballs' texels are found from: the mesh and layout generations, the
/// colour map (its identity) and the size.
pub(super) type EyesKey = (u64, u64, Option<ArcKey<HeadImage>>, u32);

/// What [`Scene::shown_colour`] was made from.
#[derive(Clone, Debug)]
pub(super) struct ShownKey {
    aged: Arc<crate::maps::mask::HeadImage>,
    /// The transition's generation and whether the hair recedes.
    transition: Option<(u64, bool)>,
}

impl PartialEq for ShownKey {
    fn eq(&self, other: &Self) -> bool {
        Arc::ptr_eq(&self.aged, &other.aged) && self.transition == other.transition
    }
}

impl Scene {
    /// The side of the aged colour map baked for maps of `map_px` (the 3D view, `agesim
    /// render`, `agesim bake`'s `albedo.png`, the GLB's base colour): the head's colour map's
    /// own side within 1024–2048 (1024 without one), not above the maps'. The colour map holds
    /// no more detail than its own size, and a spot of 2 mm is still 4–6 texels on a face at
    /// 1024²; a bake at the maps' 4096² would take ≈ 5 s and 1 GB for nothing (≈ 0.2 s at
    /// 1024², 0.7 s at 2048² on two cores).
    pub fn colour_px(&self, map_px: u32) -> u32 {
        let own = self
            .colour_map()
            .map_or(1024, |c| c.width_px.max(c.height_px));
        own.clamp(1024, 2048).min(map_px)
    }

    /// Bakes the aged base colour (docs/models.md "Skin colour") at `size`² and age `t`:
    /// the head's colour map (else the skin colour) with its age spots, uneven tone,
    /// paling and faded lips and brows ([`crate::layers::skin_colour`]); [`Scene::aged_colour`]
    /// then holds it. Redone only when the head, the size, the colour settings or an
    /// effect's age factor changed; returns whether it was.
    pub fn bake_colour(&mut self, size: u32, t: f32, cancel: &CancelToken) -> Result<bool, Error> {
        crate::maps::heightmap::check_size(size, size)?;
        let settings = self.project.colour_settings();
        let factors = self.colour_factors(t);
        let key = colour::HeadKey {
            mesh_generation: self.mesh_generation,
            layout_generation: self.layout_generation,
            metres_per_unit: self.metres_per_unit(),
        };
        let base = self.colour_map().cloned();
        let points = self.template_points();
        let template_point = |v: usize| points.get(v).copied().flatten();
        // Hair painted on the map goes and grays with the hair (measured on the scalp,
        // against the measured skin).
        let own = self.own_colours(cancel)?;
        let ages = match (own.hair, own.skin) {
            (Some(_), Some(_)) => self.pattern_alpha_at(size, size),
            _ => None,
        };
        let loss = self.hair_loss().loss;
        let shares = match loss {
            crate::layers::hair::HairLoss::Female => crate::layers::hair::FEMALE_THINNING,
            _ => (1.0, 1.0),
        };
        let thinning = self.project.hair.thinning;
        let painted = match (&ages, own.hair, own.skin) {
            (Some(ages), Some(hair), Some(skin)) => Some(crate::layers::skin_colour::PaintedHair {
                ages: ages.as_slice(),
                t,
                bald: skin.linear,
                hair: hair.linear,
                thinned: crate::layers::skin_colour::PaintedHair::thinned_at(t, thinning, shares),
                keeps_hairline: loss != crate::layers::hair::HairLoss::Male,
            }),
            _ => None,
        };
        let head = colour::Head {
            key,
            mesh: &self.inputs.mesh,
            template_point: &template_point,
            base: base.as_ref(),
            painted,
            lower_lip: self.inputs.layout.lower_lip_reach,
            painted_ages: ages.as_ref().filter(|_| painted.is_some()).map(ArcKey::of),
        };
        self.colour.bake(&head, size, &settings, &factors, cancel)
    }

    /// The hair's disappearance age per texel at `width × height`
    /// ([`crate::layers::hair::scalp::hair_age_alpha`]) of the last transition texture, in the
    /// male pattern (where the crown's hair goes): what the aged colour's painted hair reads,
    /// in every pattern (the female pattern thins the paint most where the male pattern's
    /// hair goes). `None` without hair or a transition texture. Kept per size.
    pub(super) fn pattern_alpha_at(&mut self, width: u32, height: u32) -> Option<Arc<Vec<u8>>> {
        let transition = self
            .transition
            .clone()
            .filter(|_| self.project.hair.enabled)?;
        let k = (self.transition_generation, width, height);
        if let Some((kept, a)) = &self.hair_alpha
            && *kept == k
        {
            return Some(a.clone());
        }
        let a = Arc::new(crate::layers::hair::scalp::hair_age_alpha(
            &transition,
            width,
            height,
        ));
        self.hair_alpha = Some((k, a.clone()));
        Some(a)
    }

    /// The 3D view's alpha: [`Scene::pattern_alpha_at`] in the pattern of hair loss: the
    /// hairline is kept in the female pattern or none
    /// ([`crate::layers::hair::scalp::kept_hairline_alpha`]; the female temples' small
    /// recession is the strands' alone). `None` without hair or a transition texture.
    pub(super) fn hair_alpha_at(&mut self, width: u32, height: u32) -> Option<Arc<Vec<u8>>> {
        let a = self.pattern_alpha_at(width, height)?;
        if self.hair_loss().loss == crate::layers::hair::HairLoss::Male {
            return Some(a);
        }
        Some(Arc::new(crate::layers::hair::scalp::kept_hairline_alpha(
            &a,
        )))
    }

    /// Makes [`Scene::shown_colour`] from the last [`Scene::bake_colour`] and the hair's
    /// transition texture, when either changed: what the 3D view shows (the worker and
    /// `HeadlessView` call it; exports need only the aged colour).
    pub fn prepare_shown_colour(&mut self) {
        let Some(aged) = self.colour.image.clone() else {
            self.shown = None;
            return;
        };
        let transition = self
            .transition
            .clone()
            .filter(|_| self.project.hair.enabled);
        let key = ShownKey {
            aged: aged.clone(),
            transition: transition.as_ref().map(|_| {
                (
                    self.transition_generation,
                    self.hair_loss().loss == crate::layers::hair::HairLoss::Male,
                )
            }),
        };
        if self.shown.as_ref().is_some_and(|(k, _)| *k == key) {
            return;
        }
        let alpha = transition.and_then(|_| self.hair_alpha_at(aged.width_px, aged.height_px));
        // Only skin grows hair: texels no skin triangle covers get no scalp tint. (The eyes
        // of the panel's heads, whose UVs lie beside the scalp's island, took the young
        // hair's dark tint and lost it as the hair went: "orange eye slits, new at 80",
        // blind.)
        let mut image = crate::layers::skin_colour::with_alpha(
            &aged,
            alpha.as_deref().map(Vec::as_slice),
            self.colour.texels().map(|t| &**t),
        );
        // Eyeballs that read only blank skin get an eye (the panel's "orange blank eyes").
        let eyes = self.eye_texels(&aged);
        if !eyes.is_empty() {
            let old = self.colour.factors().map_or(0.0, |f| f.pale);
            eyes.draw(&mut image, old);
        }
        self.shown = Some((key, Arc::new(image)));
    }

    /// The blank eyeballs' texels at `aged`'s size ([`crate::layers::skin_colour::EyeTexels`]),
    /// found once per mesh, layout (which parts are skin), colour map and size.
    fn eye_texels(
        &mut self,
        aged: &crate::maps::mask::HeadImage,
    ) -> Arc<crate::layers::skin_colour::EyeTexels> {
        let key = (
            self.mesh_generation,
            self.layout_generation,
            self.colour_map().map(ArcKey::of),
            aged.width_px,
        );
        if let Some((k, eyes)) = &self.eyes
            && *k == key
        {
            return eyes.clone();
        }
        let skin = self
            .colour
            .texels()
            .filter(|t| t.size() == aged.width_px)
            .cloned();
        let eyes = Arc::new(crate::layers::skin_colour::EyeTexels::new(
            &self.inputs.mesh,
            aged.width_px,
            skin.as_deref(),
            aged,
        ));
        self.eyes = Some((key, eyes.clone()));
        eyes
    }

    /// The aged colour of the last [`Scene::prepare_shown_colour`] as the 3D view shows it: its
    /// alpha is the hair's disappearance age at each texel
    /// ([`crate::layers::hair::scalp::hair_age_alpha`]), which the skin pass reads to tint the scalp
    /// under the hair (docs/models.md §9 "The scalp under the hair"). Not for export.
    pub fn shown_colour(&self) -> Option<&Arc<crate::maps::mask::HeadImage>> {
        self.shown.as_ref().map(|(_, s)| s)
    }

    /// The aged base colour of the last [`Scene::bake_colour`] (RGBA8, sRGB, in the head's
    /// UV layout).
    pub fn aged_colour(&self) -> Option<&Arc<crate::maps::mask::HeadImage>> {
        self.colour.image.as_ref()
    }

    /// The aged base colour of the last [`Scene::bake_colour`] as an export writes it: with
    /// an eye drawn on every blank eyeball, as the view shows them (without them the
    /// eyeballs of a head whose map paints none were exported blank: white or the skin's
    /// colour in Blender where the view drew eyes), without the view's hair alpha.
    pub fn exported_colour(&mut self) -> Option<Arc<crate::maps::mask::HeadImage>> {
        let aged = self.colour.image.clone()?;
        let eyes = self.eye_texels(&aged);
        if eyes.is_empty() {
            return Some(aged);
        }
        let mut image = (*aged).clone();
        let old = self.colour.factors().map_or(0.0, |f| f.pale);
        eyes.draw(&mut image, old);
        Some(Arc::new(image))
    }

    /// The texels of the last [`Scene::bake_colour`]: the regions each stands for.
    pub fn colour_texels(&self) -> Option<&Arc<crate::layers::skin_colour::SurfaceTexels>> {
        self.colour.texels()
    }

    /// The age spots placed on the head by the last [`Scene::bake_colour`] (head metres).
    pub fn age_spots(&self) -> Option<&Arc<Vec<crate::layers::skin_colour::Spot>>> {
        self.colour.spots()
    }
}
