//! Facial landmarks of a head: the anthropometric points (Farkas' names) in the mesh
//! file's own coordinates and units, read from and written to a landmark file
//! (docs/models.md "Heads"):
//!
//! ```json
//! { "landmarks": { "pronasale": [0.0012, 0.0331, 0.1093], "exocanthion_r": [-0.0465, 0.0712, 0.0741] } }
//! ```
//!
//! "Right" and "left" are the subject's own. A head may lack some points (a face mask
//! has no ears); unknown names are an error.

use std::collections::BTreeMap;
use std::path::Path;

use glam::Vec3;
use serde_json::Value;

use crate::Error;

/// Every landmark name, the face's thirteen first.
pub const NAMES: [&str; 16] = [
    "glabella",
    "nasion",
    "pronasale",
    "subnasale",
    "alare_r",
    "alare_l",
    "endocanthion_r",
    "endocanthion_l",
    "exocanthion_r",
    "exocanthion_l",
    "cheilion_r",
    "cheilion_l",
    "pogonion",
    "tragion_r",
    "tragion_l",
    "vertex",
];

/// The outer eye corners' distance in adults, metres (90–100 mm): the scale reference.
pub const EXOCANTHION_DISTANCE_M: f32 = 0.095;

/// Named points on a head, in the mesh file's coordinates.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Landmarks {
    points: BTreeMap<&'static str, Vec3>,
}

impl Landmarks {
    /// The face's height (nasion to chin, pogonion) over the outer eye corners' distance:
    /// larger in men (a longer lower face). `None` when a point is missing.
    pub fn face_ratio(&self) -> Option<f32> {
        let width = self
            .get("exocanthion_r")?
            .distance(self.get("exocanthion_l")?);
        let height = self.get("nasion")?.distance(self.get("pogonion")?);
        (width > 0.0).then(|| height / width)
    }

    /// The point named `name`, if the head has it.
    pub fn get(&self, name: &str) -> Option<Vec3> {
        self.points.get(name).copied()
    }

    /// Sets a point; `name` must be one of [`NAMES`].
    pub fn set(&mut self, name: &str, p: Vec3) -> Result<(), Error> {
        let name = known(name).ok_or_else(|| unknown(name))?;
        self.points.insert(name, p);
        Ok(())
    }

    /// How many points are placed.
    pub fn len(&self) -> usize {
        self.points.len()
    }

    pub fn is_empty(&self) -> bool {
        self.points.is_empty()
    }

    /// The distance between the outer eye corners, file units (both needed).
    pub fn exocanthion_distance(&self) -> Option<f32> {
        Some(
            self.get("exocanthion_r")?
                .distance(self.get("exocanthion_l")?),
        )
    }

    /// Reads a landmark file. Every problem names the file and the point at fault.
    pub fn load(path: &Path) -> Result<Self, Error> {
        let bytes = crate::base::limits::read_file(path, crate::base::limits::MAX_TEXT_FILE_BYTES)?;
        let err = |message: String| Error::Landmarks {
            path: path.to_owned(),
            message,
        };
        let text = String::from_utf8(bytes).map_err(|e| {
            err(format!(
                "not UTF-8 text (byte {})",
                e.utf8_error().valid_up_to()
            ))
        })?;
        Self::from_json_str(text.strip_prefix('\u{feff}').unwrap_or(&text)).map_err(err)
    }

    /// Parses the text of a landmark file; the message names the point at fault.
    pub fn from_json_str(text: &str) -> Result<Self, String> {
        let doc = crate::base::json::parse_strict(text)?;
        let Value::Object(top) = doc else {
            return Err("expected an object {\"landmarks\": {…}}".into());
        };
        if let Some(other) = top.keys().find(|k| *k != "landmarks") {
            return Err(format!(
                "unknown key `{}`: a landmark file holds only \"landmarks\"",
                crate::base::limits::shorten(other, 60)
            ));
        }
        let Some(Value::Object(points)) = top.get("landmarks") else {
            return Err("expected \"landmarks\": an object of named points".into());
        };
        Self::from_points(points)
    }

    /// The points of an object `{name: [x, y, z]}` (a landmark file's `"landmarks"`, or a
    /// project's inline `mesh.landmarks`); the message names each point at fault.
    pub fn from_points(points: &serde_json::Map<String, Value>) -> Result<Self, String> {
        let mut out = Self::default();
        let mut problems = Vec::new();
        for (name, value) in points {
            let Some(known) = known(name) else {
                problems.push(unknown(name).to_string());
                continue;
            };
            match point(value) {
                Some(p) => {
                    out.points.insert(known, p);
                }
                None => problems.push(format!(
                    "landmarks.{known}: expected [x, y, z], three finite numbers, found {}",
                    crate::base::limits::shorten(&value.to_string(), 60)
                )),
            }
        }
        if problems.is_empty() {
            Ok(out)
        } else {
            Err(problems.join("; "))
        }
    }

    /// The landmark file's text (names in [`NAMES`] order).
    pub fn to_json_pretty(&self) -> String {
        let points: serde_json::Map<String, Value> = NAMES
            .iter()
            .filter_map(|n| {
                let p = self.get(n)?;
                Some(((*n).to_owned(), Value::from(vec![p.x, p.y, p.z])))
            })
            .collect();
        let doc = serde_json::json!({ "landmarks": points });
        serde_json::to_string_pretty(&doc).unwrap_or_default()
    }
}

fn known(name: &str) -> Option<&'static str> {
    NAMES.iter().copied().find(|n| *n == name)
}

fn unknown(name: &str) -> Error {
    Error::InvalidValue {
        what: "landmark name".into(),
        value: format!("`{}`", crate::base::limits::shorten(name, 60)),
        expected: format!("one of {}", NAMES.join(", ")),
    }
}

fn point(v: &Value) -> Option<Vec3> {
    let a = v.as_array().filter(|a| a.len() == 3)?;
    let c = |i: usize| a[i].as_f64().map(|x| x as f32).filter(|x| x.is_finite());
    Some(Vec3::new(c(0)?, c(1)?, c(2)?))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn reads_what_it_writes() {
        let mut l = Landmarks::default();
        l.set("pronasale", Vec3::new(0.0012, 0.0331, 0.1093))
            .unwrap();
        l.set("exocanthion_r", Vec3::new(-0.0465, 0.0712, 0.0741))
            .unwrap();
        let back = Landmarks::from_json_str(&l.to_json_pretty()).unwrap();
        assert_eq!(back, l);
        assert_eq!(back.len(), 2);
        assert!(back.exocanthion_distance().is_none());
    }

    #[test]
    fn every_problem_names_its_point() {
        let e = Landmarks::from_json_str(
            r#"{"landmarks": {"nose": [0, 0, 0], "pogonion": [0, 1], "vertex": [0, "a", 0]}}"#,
        )
        .unwrap_err();
        for what in ["`nose`", "landmarks.pogonion", "landmarks.vertex"] {
            assert!(e.contains(what), "{what} in {e}");
        }
        for bad in [
            "[]",
            r#"{"landmarks": []}"#,
            r#"{"landmarks": {}, "extra": 1}"#,
            r#"{"landmarks": {"nasion": [0, 0, 0]}, "landmarks": {}}"#,
            "{",
        ] {
            assert!(Landmarks::from_json_str(bad).is_err(), "{bad}");
        }
    }

    #[test]
    fn a_missing_file_names_its_path() {
        let e = Landmarks::load(Path::new("/no/such/l.json")).unwrap_err();
        assert!(e.to_string().contains("/no/such/l.json"), "{e}");
    }
}
