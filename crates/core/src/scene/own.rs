//! What the scene knows of the person whose head it ages (docs/models.md "The head's own
//! colours", §9 "Hair loss"): the colours measured on the head's colour map (skin, hair,
//! brows), the colours the hair and brows are drawn in (the project's, else measured, else
//! a default), how much later dark hair grays, and the pattern of hair loss (the
//! project's, else guessed from the face's proportions).

use super::*;
use crate::base::lab::lab;
use crate::head::frame::Regions;
use crate::layers::hair::HairLoss;
use crate::layers::skin_colour::{BaseColour, Face, Measured, OwnColours, SurfaceTexels};
use crate::maps::mask::HeadImage;

/// The side of the texels the colours are measured on: enough for a brow (a few hundred
/// texels of a 512² layout), a fraction of a bake.
const MEASURE_PX: u32 = 512;

/// The hair's colour when neither the project nor the head gives one: dark brown, the most
/// common hair colour.
pub const FALLBACK_HAIR: crate::project::Colour = crate::project::Colour([0x3f, 0x2c, 0x1f]);

/// How dark the brows are against the hair when the head does not show its own (brows are
/// darker than the scalp's hair).
pub const BROW_DARKNESS: f32 = 0.7;

/// The key of the measured colours: mesh and layout generations, the colour map's identity.
pub(super) type OwnKey = (u64, u64, Option<ArcKey<HeadImage>>);

/// Where a colour the hair or brows are drawn in comes from.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Source {
    /// The project's value.
    Project,
    /// Measured on the head's colour map.
    Measured,
    /// Neither: the default (the hair's, for the brows).
    Default,
}

impl Source {
    /// Where a colour comes from, for reports: `measured_on` the region it is measured on
    /// (`scalp`, `brows`), `default` what stands in without one.
    pub fn describe(self, measured_on: &str, default: &str) -> String {
        match self {
            Self::Project => "set in the project".into(),
            Self::Measured => format!("measured on the colour map's {measured_on}"),
            Self::Default => {
                format!("{default}: the head's colour map shows none on its {measured_on}")
            }
        }
    }
}

/// What the scene draws of the person ([`Scene::person`]): the hair's and the brows'
/// colours before graying (linear) and where each comes from, how many years later than
/// the project's range the hair grays (darker hair later), the pattern of hair loss.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Person {
    pub hair: [f32; 3],
    pub hair_source: Source,
    pub brows: [f32; 3],
    pub brow_source: Source,
    pub graying_delay_years: f32,
    pub loss: LossChoice,
    /// The skin's CIELAB lightness: measured on the cheeks, else the project's skin colour.
    pub skin_l: f32,
    /// How curled the hair is, 0–1, and whether it was guessed from this ITA° of the skin
    /// (the project's `hair.curl` is null; [`crate::layers::hair::guess_curl`]).
    pub curl: f32,
    pub curl_guessed: Option<f32>,
}

/// The pattern of hair loss a scene uses and where it comes from.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct LossChoice {
    pub loss: HairLoss,
    /// Guessed (the project's `hair.loss` is null), from this face ratio
    /// ([`Landmarks::face_ratio`]; `None`: no face to measure: male, the template's).
    pub guessed: Option<Option<f32>>,
}

impl LossChoice {
    pub fn describe(&self) -> String {
        match self.guessed {
            None => format!("{} (set in the project)", self.loss.name()),
            Some(Some(r)) => format!(
                "{} (guessed from the face: height / eye width {r:.2}, male from {}; set hair.loss to change)",
                self.loss.name(),
                crate::layers::hair::MALE_FACE_RATIO
            ),
            Some(None) => format!(
                "{} (guessed: no face to measure; set hair.loss to change)",
                self.loss.name()
            ),
        }
    }
}

impl Scene {
    /// The head's own colours measured on its colour map (all `None` without one), made
    /// once per head and map.
    pub fn own_colours(&mut self, cancel: &CancelToken) -> Result<Arc<OwnColours>, Error> {
        let map = self.colour_map().cloned();
        let key: OwnKey = (
            self.mesh_generation,
            self.layout_generation,
            map.as_ref().map(ArcKey::of),
        );
        if let Some((k, own)) = &self.own
            && *k == key
        {
            return Ok(own.clone());
        }
        let own = match map {
            None => Arc::new(OwnColours::default()),
            Some(map) => Arc::new(self.measure(&map, cancel)?),
        };
        self.own = Some((key, own.clone()));
        Ok(own)
    }

    fn measure(
        &mut self,
        map: &crate::maps::mask::HeadImage,
        cancel: &CancelToken,
    ) -> Result<OwnColours, Error> {
        let Some(regions) = Regions::template() else {
            return Ok(OwnColours::default());
        };
        let points = self.template_points();
        let template_point = |v: usize| points.get(v).copied().flatten();
        let texels = SurfaceTexels::new(
            &self.inputs.mesh,
            &template_point,
            self.metres_per_unit(),
            MEASURE_PX,
            Face {
                regions,
                drawn_crease: &|_| 0.0,
                lower_lip: self.inputs.layout.lower_lip_reach,
            },
            self.project.skin.colour_seed,
            cancel,
        )?;
        let base = BaseColour::new(Some(map), self.project.skin.albedo.linear(), &texels);
        // The scalp: the hair's region at the young end, in the head's layout (the
        // transition's own size, so its correspondence is the one the hair uses).
        let Some(masks) = self.inputs.hair_masks.clone() else {
            return Ok(crate::layers::skin_colour::measure(&base, &texels, &|_| {
                false
            }));
        };
        let outer = &masks.0;
        let size = super::hair::transition_size(
            self.project.hair.transition_size_px,
            outer,
            &masks.1,
            self.udim_grid(),
        );
        let (values, side) = match self.correspondence(size, cancel)? {
            Some(c) => (
                c.resample(outer.values(), outer.width_px(), outer.height_px()),
                (size, size),
            ),
            None => (
                outer.values().to_vec(),
                (outer.width_px(), outer.height_px()),
            ),
        };
        let n = MEASURE_PX as usize;
        let scalp = |i: usize| {
            let (x, y) = (i % n, i / n);
            let sx = ((x as f32 + 0.5) / n as f32 * side.0 as f32) as usize;
            let sy = ((y as f32 + 0.5) / n as f32 * side.1 as f32) as usize;
            values
                .get(sy.min(side.1 as usize - 1) * side.0 as usize + sx.min(side.0 as usize - 1))
                .is_some_and(|&v| v >= crate::layers::hair::transition::REGION_THRESHOLD)
        };
        Ok(crate::layers::skin_colour::measure(&base, &texels, &scalp))
    }

    /// The person as the last [`Scene::own_colours`] measured them (nothing measured
    /// before it, or since the head or its map changed: the project's values and the
    /// defaults). [`Scene::bake`] measures first, so a frame drawn after a bake has them.
    pub fn person(&self) -> Person {
        let key: OwnKey = (
            self.mesh_generation,
            self.layout_generation,
            self.colour_map().map(ArcKey::of),
        );
        let own = match &self.own {
            Some((k, own)) if *k == key => **own,
            _ => OwnColours::default(),
        };
        let h = &self.project.hair;
        let (hair, hair_source) = match (h.base_colour, own.hair) {
            (Some(c), _) => (c.linear(), Source::Project),
            (None, Some(m)) => (m.linear.to_array(), Source::Measured),
            (None, None) => (FALLBACK_HAIR.linear(), Source::Default),
        };
        let (brows, brow_source) = match (h.brow_colour, own.brows) {
            (Some(c), _) => (c.linear(), Source::Project),
            (None, Some(m)) => (m.linear.to_array(), Source::Measured),
            (None, None) => (hair.map(|c| c * BROW_DARKNESS), Source::Default),
        };
        let skin_lab = own.skin.map_or_else(
            || lab(glam::Vec3::from(self.project.skin.albedo.linear())),
            |m| m.lab,
        );
        let ita = crate::base::lab::ita_degrees(skin_lab);
        Person {
            hair,
            hair_source,
            brows,
            brow_source,
            graying_delay_years: crate::layers::hair::graying_delay_years(
                lab(glam::Vec3::from(hair)).x,
            ),
            loss: self.hair_loss(),
            skin_l: skin_lab.x,
            curl: h.curl.map_or_else(
                || crate::layers::hair::guess_curl(ita),
                |c| c.clamp(0.0, 1.0),
            ),
            curl_guessed: h.curl.is_none().then_some(ita),
        }
    }

    /// [`Scene::person`] after measuring the head's colours if they are not yet.
    pub fn measure_person(&mut self, cancel: &CancelToken) -> Result<Person, Error> {
        self.own_colours(cancel)?;
        Ok(self.person())
    }

    /// The aged colour's factors at age `t` for this person's hair
    /// ([`Project::colour_factors_with_delay`]).
    pub fn colour_factors(&self, t: f32) -> crate::age::ColourFactors {
        self.project
            .colour_factors_with_delay(t, self.person().graying_delay_years)
    }

    /// The pattern of hair loss: the project's `hair.loss`, else guessed from the face
    /// (the fitted landmarks; the template's for a head read at its own UVs).
    pub fn hair_loss(&self) -> LossChoice {
        if let Some(loss) = self.project.hair.loss {
            return LossChoice {
                loss,
                guessed: None,
            };
        }
        let template = crate::head::fit::template();
        let ratio = match (&self.inputs.layout.landmarks, &self.inputs.layout.fit) {
            (Some(l), _) => l.face_ratio(),
            (None, None) if self.project.mesh.path.is_none() => template.landmarks.face_ratio(),
            _ => None,
        };
        LossChoice {
            loss: ratio.map_or(HairLoss::Male, HairLoss::guess),
            guessed: Some(ratio),
        }
    }
}

/// A measured colour as `mesh-info` prints it: `#rrggbb (L* a* b*)`.
pub fn describe_measured(m: &Measured) -> String {
    format!(
        "{} (L* {:.0}, a* {:.0}, b* {:.0}; {} texels)",
        m.hex(),
        m.lab.x,
        m.lab.y,
        m.lab.z,
        m.texels
    )
}
