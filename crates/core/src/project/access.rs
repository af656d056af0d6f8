//! One field of a [`Project`] by its JSON path, typed: read ([`Project::field`]) and set
//! with the checks of a project file ([`Project::set_field`]), without serialising or
//! re-validating the whole project. The editor's layer panel and its undo steps work on
//! the project through these; `tests` checks the table against `fields::FIELDS` and the
//! serialised project, so a new field cannot be forgotten here.

use serde::Serialize;
use serde::de::DeserializeOwned;
use serde_json::Value;

use super::{Project, fields};
use crate::Error;

/// A field's value as JSON, one field at a time.
trait Slot {
    fn get(&self) -> Value;
    fn set(&mut self, value: Value) -> Result<(), String>;
}

impl<T: Serialize + DeserializeOwned> Slot for T {
    fn get(&self) -> Value {
        // A number, a name, a path or a list of paths: serialising cannot fail.
        serde_json::to_value(self).unwrap_or(Value::Null)
    }

    fn set(&mut self, value: Value) -> Result<(), String> {
        *self = serde_json::from_value(value).map_err(|e| e.to_string())?;
        Ok(())
    }
}

/// The table: each JSON path and the project member it names.
macro_rules! slots {
    ($($path:literal => $($member:ident).+;)*) => {
        fn slot<'a>(p: &'a Project, path: &str) -> Option<&'a dyn Slot> {
            match path {
                $($path => Some(&p.$($member).+),)*
                _ => None,
            }
        }

        fn slot_mut<'a>(p: &'a mut Project, path: &str) -> Option<&'a mut dyn Slot> {
            match path {
                $($path => Some(&mut p.$($member).+),)*
                _ => None,
            }
        }

        #[cfg(test)]
        const PATHS: &[&str] = &[$($path),*];
    };
}

slots! {
    "version" => version;
    "map_size_mm" => map_size_mm;
    "seed" => seed;
    "tile" => tile;
    "mesh.path" => mesh.path;
    "mesh.builtin" => mesh.builtin;
    "mesh.metres_per_unit" => mesh.metres_per_unit;
    "mesh.landmarks" => mesh.landmarks;
    "mesh.up" => mesh.up;
    "mesh.forward" => mesh.forward;
    "mesh.layout" => mesh.layout;
    "mesh.colour_map" => mesh.colour_map;
    "mesh.normal_map" => mesh.normal_map;
    "mesh.normal_map_convention" => mesh.normal_map_convention;
    "mesh.skin_parts" => mesh.skin_parts;
    "mesh.maps_flip_v" => mesh.maps_flip_v;
    "large.enabled" => large.enabled;
    "large.wrinkles" => large.wrinkles;
    "large.mask" => large.mask;
    "large.gamma" => large.gamma;
    "large.depth" => large.depth;
    "pores.enabled" => pores.enabled;
    "pores.count" => pores.count;
    "pores.density_per_cm2" => pores.density_per_cm2;
    "pores.placement" => pores.placement;
    "pores.profile" => pores.profile;
    "pores.rim" => pores.rim;
    "furrows.enabled" => furrows.enabled;
    "furrows.links_per_pore" => furrows.links_per_pore;
    "furrows.max_count" => furrows.max_count;
    "furrows.direction_deg" => furrows.direction_deg;
    "furrows.direction_strength" => furrows.direction_strength;
    "furrows.taper" => furrows.taper;
    "noise.details" => noise.details;
    "noise.roughness" => noise.roughness;
    "noise.lacunarity" => noise.lacunarity;
    "noise.scale_mm" => noise.scale_mm;
    "noise.strength" => noise.strength;
    "warp.strength_mm" => warp.strength_mm;
    "warp.details" => warp.details;
    "warp.roughness" => warp.roughness;
    "warp.lacunarity" => warp.lacunarity;
    "warp.scale_mm" => warp.scale_mm;
    "overlap.beta" => overlap.beta;
    "overlap.n" => overlap.n;
    "normal.strength" => normal.strength;
    "normal.convention" => normal.convention;
    "fine.enabled" => fine.enabled;
    "fine.tile" => fine.tile;
    "fine.size_mm" => fine.size_mm;
    "fine.strength" => fine.strength;
    "fine.size_px" => fine.size_px;
    "fine.creases" => fine.creases;
    "fine.length" => fine.length;
    "fine.width" => fine.width;
    "fine.crossing_deg" => fine.crossing_deg;
    "fine.spread_deg" => fine.spread_deg;
    "fine.seed" => fine.seed;
    "hair.enabled" => hair.enabled;
    "hair.outer_mask" => hair.outer_mask;
    "hair.inner_mask" => hair.inner_mask;
    "hair.density_per_cm2" => hair.density_per_cm2;
    "hair.metric" => hair.metric;
    "hair.transition_size_px" => hair.transition_size_px;
    "hair.seed" => hair.seed;
    "hair.max_deviation_deg" => hair.max_deviation_deg;
    "hair.length_mm" => hair.length_mm;
    "hair.base_colour" => hair.base_colour;
    "hair.gray_colour" => hair.gray_colour;
    "hair.graying_onset_min_years" => hair.graying_onset_min_years;
    "hair.graying_onset_max_years" => hair.graying_onset_max_years;
    "hair.graying_ramp" => hair.graying_ramp;
    "hair.thinning" => hair.thinning;
    "hair.taper_mm" => hair.taper_mm;
    "hair.scalp_tint" => hair.scalp_tint;
    "hair.brows" => hair.brows;
    "hair.k_diff" => hair.k_diff;
    "hair.k_spec" => hair.k_spec;
    "hair.shininess" => hair.shininess;
    "hair.k_amb" => hair.k_amb;
    "skin.albedo" => skin.albedo;
    "skin.pale_albedo" => skin.pale_albedo;
    "skin.pale_amount" => skin.pale_amount;
    "skin.spots_per_cm2" => skin.spots_per_cm2;
    "skin.spot_strength" => skin.spot_strength;
    "skin.mottle" => skin.mottle;
    "skin.redness" => skin.redness;
    "skin.under_eye" => skin.under_eye;
    "skin.yellowing" => skin.yellowing;
    "skin.contrast_loss" => skin.contrast_loss;
    "skin.colour_seed" => skin.colour_seed;
    "skin.subsurface_colour" => skin.subsurface_colour;
    "skin.wrap" => skin.wrap;
    "skin.roughness" => skin.roughness;
    "skin.specular" => skin.specular;
    "age.t" => age.t;
    "age.young_years" => age.young_years;
    "age.old_years" => age.old_years;
    "age.pores_young_scale" => age.pores_young_scale;
    "age.furrows_young_scale" => age.furrows_young_scale;
    "shape.enabled" => shape.enabled;
    "shape.strength" => shape.strength;
    "shape.brows" => shape.brows;
    "shape.lids" => shape.lids;
    "shape.bags" => shape.bags;
    "shape.tear_trough" => shape.tear_trough;
    "shape.temples" => shape.temples;
    "shape.cheeks" => shape.cheeks;
    "shape.jowls" => shape.jowls;
    "shape.lips" => shape.lips;
    "shape.nose" => shape.nose;
    "shape.ears" => shape.ears;
    "shape.neck" => shape.neck;
    "view.pom" => view.pom;
    "view.linear_steps" => view.linear_steps;
    "view.binary_steps" => view.binary_steps;
    "view.disp_scale" => view.disp_scale;
    "view.light_yaw_deg" => view.light_yaw_deg;
    "view.light_pitch_deg" => view.light_pitch_deg;
    "view.fill_light" => view.fill_light;
    "view.shadows" => view.shadows;
    "view.camera_yaw_deg" => view.camera_yaw_deg;
    "view.camera_pitch_deg" => view.camera_pitch_deg;
    "view.camera_distance_m" => view.camera_distance_m;
    "view.fov_deg" => view.fov_deg;
    "view.show_hair" => view.show_hair;
    "view.wireframe" => view.wireframe;
    "age.large.onset_years" => age.large.onset_years;
    "age.large.full_years" => age.large.full_years;
    "age.large.shape" => age.large.shape;
    "age.fine.onset_years" => age.fine.onset_years;
    "age.fine.full_years" => age.fine.full_years;
    "age.fine.shape" => age.fine.shape;
    "age.pores.onset_years" => age.pores.onset_years;
    "age.pores.full_years" => age.pores.full_years;
    "age.pores.shape" => age.pores.shape;
    "age.furrows.onset_years" => age.furrows.onset_years;
    "age.furrows.full_years" => age.furrows.full_years;
    "age.furrows.shape" => age.furrows.shape;
    "age.pale.onset_years" => age.pale.onset_years;
    "age.pale.full_years" => age.pale.full_years;
    "age.pale.shape" => age.pale.shape;
    "age.spots.onset_years" => age.spots.onset_years;
    "age.spots.full_years" => age.spots.full_years;
    "age.spots.shape" => age.spots.shape;
    "age.mottle.onset_years" => age.mottle.onset_years;
    "age.mottle.full_years" => age.mottle.full_years;
    "age.mottle.shape" => age.mottle.shape;
    "age.redness.onset_years" => age.redness.onset_years;
    "age.redness.full_years" => age.redness.full_years;
    "age.redness.shape" => age.redness.shape;
    "age.contrast.onset_years" => age.contrast.onset_years;
    "age.contrast.full_years" => age.contrast.full_years;
    "age.contrast.shape" => age.contrast.shape;
    "pores.elongation" => pores.elongation;
    "furrows.anisotropy" => furrows.anisotropy;
    "pores.radius_mm.mean" => pores.radius_mm.mean;
    "pores.radius_mm.spread" => pores.radius_mm.spread;
    "pores.depth.mean" => pores.depth.mean;
    "pores.depth.spread" => pores.depth.spread;
    "pores.falloff.mean" => pores.falloff.mean;
    "pores.falloff.spread" => pores.falloff.spread;
    "furrows.depth.mean" => furrows.depth.mean;
    "furrows.depth.spread" => furrows.depth.spread;
    "furrows.width_mm.mean" => furrows.width_mm.mean;
    "furrows.width_mm.spread" => furrows.width_mm.spread;
}

impl Project {
    /// The value of the field at `path` (`noise.details`) as JSON, or `None` for a path
    /// that names no field. Only that field is serialised.
    pub fn field(&self, path: &str) -> Option<Value> {
        slot(self, path).map(Slot::get)
    }

    /// Sets the field at `path` to `value`, checked as a project file checks it: its type
    /// and range, then the rules between fields (e.g. `age.old_years` > `young_years`).
    /// On an error the project is unchanged and the message names the field.
    pub fn set_field(&mut self, path: &str, value: Value) -> Result<(), Error> {
        let err = |message: String| Error::Project {
            source_name: path.to_owned(),
            message,
        };
        let field = fields::find(path).map_err(err)?;
        field.check(&value).map_err(err)?;
        let before = self.clone();
        let slot = slot_mut(self, path).ok_or_else(|| err(format!("`{path}` cannot be set")))?;
        slot.set(value).map_err(|e| err(format!("{path}: {e}")))?;
        let mut problems = Vec::new();
        self.check_consistency(&mut problems);
        if problems.is_empty() {
            return Ok(());
        }
        *self = before;
        Err(err(problems.join("; ")))
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::project::json::get_path;

    /// Every field of the table reads what the serialised project holds, and every field
    /// of `FIELDS` is in the table.
    #[test]
    fn the_table_covers_every_field_and_reads_what_serde_writes() {
        let mut p = Project::default();
        p.noise.details = 3.25;
        p.large.wrinkles = vec!["a.wrk".into(), "b.wrk".into()];
        p.hair.transition_size_px = Some(512);
        let doc = p.to_value();
        for field in fields::FIELDS.iter() {
            assert!(
                PATHS.contains(&field.path),
                "{} is not in the table",
                field.path
            );
            assert_eq!(
                p.field(field.path).as_ref(),
                get_path(&doc, field.path),
                "{}",
                field.path
            );
        }
        assert_eq!(PATHS.len(), fields::FIELDS.len());
    }

    /// A typed set gives the project a whole-document set gives, and refuses what it
    /// refuses, leaving the project as it was.
    #[test]
    fn set_field_agrees_with_the_document_route() {
        let base = Project::default();
        for (path, value) in [
            ("noise.details", Value::from(2.5)),
            ("pores.count", Value::from(900)),
            ("pores.density_per_cm2", Value::from(40.0)),
            ("pores.density_per_cm2", Value::Null),
            ("view.pom", Value::from("binary")),
            ("skin.albedo", Value::from("#c08070")),
            ("large.wrinkles", Value::from(vec!["x.wrk"])),
            ("age.fine.onset_years", Value::from(33.0)),
        ] {
            let mut typed = base.clone();
            typed.set_field(path, value.clone()).unwrap();
            let mut doc = base.to_value();
            crate::project::json::set_path(&mut doc, path, value).unwrap();
            assert_eq!(typed, Project::from_value(doc, "test").unwrap(), "{path}");
        }
        for (path, value) in [
            ("pores.count", Value::from(-3)),
            ("noise.details", Value::from("many")),
            ("noise.details", Value::from(99.0)),
            ("view.pom", Value::from("fast")),
            // Before young_years: a rule between two fields.
            ("age.old_years", Value::from(10.0)),
            ("no.such", Value::from(1)),
        ] {
            let mut p = base.clone();
            let e = p.set_field(path, value).unwrap_err().to_string();
            assert!(e.contains(path.split('.').next().unwrap()), "{e}");
            assert_eq!(p, base, "{path} left a change");
        }
    }
}
