//! One field of a [`Project`] by its JSON path, typed: read ([`Project::field`]) and set
//! with the checks of a project file ([`Project::set_field`]), without serialising or
//! re-validating the whole project, through the accessors of its row in `fields::FIELDS`.
//! The editor's layer panel and its undo steps work on the project through these; `tests`
//! checks every row against the serialised project, and every member the project
//! serialises against the table, so a new field cannot be forgotten in either.

use serde_json::Value;

use super::{Project, fields};
use crate::Error;

impl Project {
    /// The value of the field at `path` (`noise.details`) as JSON, or `None` for a path
    /// that names no field. Only that field is serialised.
    pub fn field(&self, path: &str) -> Option<Value> {
        let field = fields::find(path).ok()?;
        Some((field.get)(self))
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
        (field.set)(self, value).map_err(|e| err(format!("{path}: {e}")))?;
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

    /// Every row of the table reads what the serialised project holds at its path (a row
    /// without its member does not compile; a member without its row fails
    /// `the_table_covers_every_field_of_the_project_exactly_once`).
    #[test]
    fn the_table_covers_every_field_and_reads_what_serde_writes() {
        let mut p = Project::default();
        p.noise.details = 3.25;
        p.large.wrinkles = vec!["a.wrk".into(), "b.wrk".into()];
        p.hair.transition_size_px = Some(512);
        let doc = p.to_value();
        for field in fields::FIELDS.iter() {
            assert_eq!(
                p.field(field.path).as_ref(),
                get_path(&doc, field.path),
                "{}",
                field.path
            );
        }
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
