//! The one table of project fields: JSON path, the project member it names (read and set
//! one field at a time, [`super::Project::field`]), unit, range, meaning. It drives the type
//! and range checks of [`super::Project`], `--set`, the generated `docs/project-file.md`
//! ([`markdown`]), the editor's sliders and tooltips and the timeline's age curves
//! ([`age_curves`]). A row's path is made from the member it names (`id!(pores.count)`), so
//! the two cannot disagree. Defaults are not repeated here: they are read from
//! `Project::default()` ([`Field::default_value`]), so there is one copy.

mod table;

pub use table::{FIELDS, SECTIONS};

use serde::Serialize;
use serde::de::DeserializeOwned;
use serde_json::Value;

use super::Project;
use super::json::{get_path, type_name};

/// A project member read and set as JSON, one field at a time.
pub(crate) trait Slot {
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

/// A field's JSON path and its accessors ([`id`]).
#[derive(Clone, Copy)]
pub(crate) struct Id {
    pub path: &'static str,
    pub get: fn(&Project) -> Value,
    pub set: fn(&mut Project, Value) -> Result<(), String>,
}

/// The [`Id`] of the project member `a.b.c`: its JSON path `"a.b.c"` and its accessors.
macro_rules! id {
    ($first:ident $(. $rest:ident)*) => {
        $crate::project::fields::Id {
            path: concat!(stringify!($first) $(, ".", stringify!($rest))*),
            get: |p| $crate::project::fields::Slot::get(&p.$first $(.$rest)*),
            set: |p, v| $crate::project::fields::Slot::set(&mut p.$first $(.$rest)*, v),
        }
    };
}
pub(crate) use id;

/// What a field holds, with its valid range.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Kind {
    /// A number in `min..=max`.
    Float {
        min: f32,
        max: f32,
    },
    /// An integer in `min..=max`.
    Int {
        min: u64,
        max: u64,
    },
    /// A number in `min..=max`, or `null` (off / automatic).
    OptFloat {
        min: f32,
        max: f32,
    },
    /// An integer in `min..=max`, or `null`.
    OptInt {
        min: u64,
        max: u64,
    },
    Bool,
    /// One of these names.
    Choice(&'static [&'static str]),
    /// A file path, or `null` for the built-in default.
    Path,
    /// A list of file paths.
    Paths,
    /// An sRGB colour `"#rrggbb"`.
    Colour,
    /// An sRGB colour `"#rrggbb"`, or `null` (measured on the head).
    OptColour,
    /// One of these names, or `null` (guessed from the head).
    OptChoice(&'static [&'static str]),
    /// A landmark file's path, the points themselves (`{name: [x, y, z]}`), or `null`.
    Landmarks,
    /// A list of names, or `null` (chosen automatically).
    OptNames,
}

/// One field of the project file.
#[derive(Clone, Copy)]
pub struct Field {
    /// The JSON path, e.g. `pores.radius_mm.mean`.
    pub path: &'static str,
    /// Unit, or `""` for none.
    pub unit: &'static str,
    pub kind: Kind,
    /// One line: what it does.
    pub doc: &'static str,
    /// The member's value as JSON.
    pub(crate) get: fn(&Project) -> Value,
    /// Sets the member from JSON (its type only: [`Project::set_field`] checks the rest).
    pub(crate) set: fn(&mut Project, Value) -> Result<(), String>,
}

impl std::fmt::Debug for Field {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("Field")
            .field("path", &self.path)
            .field("unit", &self.unit)
            .field("kind", &self.kind)
            .finish_non_exhaustive()
    }
}

impl PartialEq for Field {
    fn eq(&self, other: &Self) -> bool {
        (self.path, self.unit, self.kind, self.doc)
            == (other.path, other.unit, other.kind, other.doc)
    }
}

/// One age curve of the project ([`age_curves`]).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct AgeCurveRow {
    /// Its path, e.g. `age.large` (its fields are `age.large.onset_years`, …).
    pub path: &'static str,
    /// What it drives, short: the table's words before any parenthesis.
    pub what: &'static str,
    pub curve: crate::age::AgeCurve,
}

/// The project's age curves as the table lists them (the `curve!` rows under `age.`), in
/// document order, with their values in `project`. The timeline draws these.
pub fn age_curves(project: &Project) -> Vec<AgeCurveRow> {
    FIELDS
        .iter()
        .filter_map(|f| {
            let path = f.path.strip_suffix(".onset_years")?;
            let what = f.doc.strip_suffix(": age at which it starts")?;
            let what = what.split(" (").next().unwrap_or(what);
            let part = |name: &str| project.field(&format!("{path}.{name}"));
            let value = serde_json::json!({
                "onset_years": part("onset_years")?,
                "full_years": part("full_years")?,
                "shape": part("shape")?,
            });
            let curve = serde_json::from_value(value).ok()?;
            Some(AgeCurveRow { path, what, curve })
        })
        .collect()
}

/// The field at `path`, or an error naming the closest fields.
pub fn find(path: &str) -> Result<&'static Field, String> {
    if let Some(field) = FIELDS.iter().find(|f| f.path == path) {
        return Ok(field);
    }
    let shown = crate::base::limits::shorten(path, 80);
    let prefix = format!("{path}.");
    let below: Vec<&str> = FIELDS
        .iter()
        .filter(|f| f.path.starts_with(&prefix))
        .map(|f| f.path)
        .collect();
    if !below.is_empty() {
        return Err(format!(
            "`{shown}` is a group of fields: set one of {}",
            below.join(", ")
        ));
    }
    let section = path.split('.').next().unwrap_or("");
    let near: Vec<&str> = FIELDS
        .iter()
        .filter(|f| f.path.split('.').next() == Some(section))
        .map(|f| f.path)
        .collect();
    Err(if near.is_empty() {
        format!("unknown field `{shown}`; see docs/project-file.md")
    } else {
        format!(
            "unknown field `{shown}`; expected one of: {}",
            near.join(", ")
        )
    })
}

impl Field {
    /// The default value, from `Project::default()`.
    pub fn default_value(&self) -> Value {
        let d = super::Project::default().to_value();
        get_path(&d, self.path).cloned().unwrap_or(Value::Null)
    }

    /// The range for messages and docs.
    pub fn range_text(&self) -> String {
        match self.kind {
            Kind::Float { min, max } => format!("{min}..={max}"),
            Kind::Int { min, max } if max == u64::MAX => format!("an integer ≥ {min}"),
            Kind::Int { min, max } => format!("an integer in {min}..={max}"),
            Kind::OptFloat { min, max } => format!("{min}..={max} or null"),
            Kind::OptInt { min, max } => format!("an integer in {min}..={max} or null"),
            Kind::Bool => "true or false".into(),
            Kind::Choice(names) => format!("one of {}", names.join(", ")),
            Kind::Path => "a path or null".into(),
            Kind::Paths => "a list of paths".into(),
            Kind::Colour => "\"#rrggbb\"".into(),
            Kind::OptColour => "\"#rrggbb\" or null".into(),
            Kind::OptChoice(names) => format!("one of {} or null", names.join(", ")),
            Kind::OptNames => "a list of names or null".into(),
            Kind::Landmarks => "a path, {name: [x, y, z]} or null".into(),
        }
    }

    /// What a JSON value of this field must look like (its type, not its range).
    fn type_text(&self) -> &'static str {
        match self.kind {
            Kind::Float { .. } => "a number",
            Kind::Int { .. } => "an integer",
            Kind::OptFloat { .. } => "a number or null",
            Kind::OptInt { .. } => "an integer or null",
            Kind::Bool => "true or false",
            Kind::Choice(_) => "a name",
            Kind::Path => "a path (string) or null",
            Kind::Paths => "a list of paths",
            Kind::Colour => "a colour \"#rrggbb\"",
            Kind::OptColour => "a colour \"#rrggbb\" or null",
            Kind::OptChoice(_) => "a name or null",
            Kind::OptNames => "a list of names or null",
            Kind::Landmarks => "a path (string), an object {name: [x, y, z]} or null",
        }
    }

    fn type_ok(&self, v: &Value) -> bool {
        match self.kind {
            Kind::Float { .. } => v.is_number(),
            Kind::Int { .. } => v.is_u64(),
            Kind::OptFloat { .. } => v.is_number() || v.is_null(),
            Kind::OptInt { .. } => v.is_u64() || v.is_null(),
            Kind::Bool => v.is_boolean(),
            Kind::Choice(_) | Kind::Colour => v.is_string(),
            Kind::OptChoice(_) | Kind::OptColour => v.is_string() || v.is_null(),
            Kind::Path => v.is_string() || v.is_null(),
            Kind::Paths => v.as_array().is_some_and(|a| a.iter().all(Value::is_string)),
            Kind::OptNames => {
                v.is_null() || v.as_array().is_some_and(|a| a.iter().all(Value::is_string))
            }
            Kind::Landmarks => v.is_null() || v.is_string() || v.is_object(),
        }
    }

    /// The range problem of a well-typed value, if any.
    fn range_problem(&self, v: &Value) -> Option<String> {
        if let (Kind::Landmarks, Value::Object(points)) = (self.kind, v) {
            // Each point named as in a landmark file, three finite numbers.
            return crate::head::landmarks::Landmarks::from_points(points)
                .err()
                .map(|e| format!("{}: {e}", self.path));
        }
        let ok = match self.kind {
            // A plain number field holding null here was not finite (serialised from an
            // infinite or NaN value).
            Kind::Float { min, max } => v
                .as_f64()
                .is_some_and(|x| x >= min as f64 && x <= max as f64),
            Kind::OptFloat { min, max } => match v.as_f64() {
                None => v.is_null(),
                Some(x) => x >= min as f64 && x <= max as f64,
            },
            Kind::Int { min, max } | Kind::OptInt { min, max } => match v.as_u64() {
                None => v.is_null(),
                Some(x) => x >= min && x <= max,
            },
            Kind::Choice(names) => v.as_str().is_some_and(|s| names.contains(&s)),
            Kind::Colour => v.as_str().and_then(super::Colour::parse).is_some(),
            Kind::OptColour => v.is_null() || v.as_str().and_then(super::Colour::parse).is_some(),
            Kind::OptChoice(names) => v.is_null() || v.as_str().is_some_and(|s| names.contains(&s)),
            Kind::Bool | Kind::Path | Kind::Paths | Kind::OptNames | Kind::Landmarks => true,
        };
        (!ok).then(|| {
            format!(
                "{} = {} is out of range: expected {}",
                self.path,
                quote(v),
                self.range_text()
            )
        })
    }

    /// Checks one value of this field: its type, then its range. The message names the
    /// field (`pores.count: expected an integer, found number -3`).
    pub fn check(&self, v: &Value) -> Result<(), String> {
        if !self.type_ok(v) {
            return Err(format!(
                "{}: expected {}, found {} {}",
                self.path,
                self.type_text(),
                type_name(v),
                quote(v)
            ));
        }
        match self.range_problem(v) {
            Some(p) => Err(p),
            None => Ok(()),
        }
    }

    /// Reads a value typed on the command line as this field's type.
    pub fn parse_text(&self, text: &str) -> Result<Value, String> {
        // A JSON string literal (`"a b.wrk"`) stands for its contents.
        let decoded = serde_json::from_str::<String>(text.trim()).ok();
        let t = decoded.as_deref().unwrap_or(text.trim());
        let bad = || {
            format!(
                "{}: expected {} ({}), found `{}`",
                self.path,
                self.type_text(),
                self.range_text(),
                crate::base::limits::shorten(t, 60)
            )
        };
        let number = || {
            t.parse::<f64>()
                .ok()
                .filter(|x| x.is_finite())
                .and_then(serde_json::Number::from_f64)
                .map(Value::Number)
        };
        let value = match self.kind {
            Kind::Float { .. } => number(),
            Kind::OptFloat { .. } if t == "null" => Some(Value::Null),
            Kind::OptFloat { .. } => number(),
            Kind::Int { .. } => t.parse::<u64>().ok().map(Value::from),
            Kind::OptInt { .. } if t == "null" => Some(Value::Null),
            Kind::OptInt { .. } => t.parse::<u64>().ok().map(Value::from),
            Kind::Bool => t.parse::<bool>().ok().map(Value::Bool),
            Kind::Choice(_) | Kind::Colour => Some(Value::String(t.to_owned())),
            Kind::OptChoice(_) | Kind::OptColour if t == "null" => Some(Value::Null),
            Kind::OptChoice(_) | Kind::OptColour => Some(Value::String(t.to_owned())),
            Kind::Path | Kind::Landmarks if t == "null" => Some(Value::Null),
            // An object typed as such (a quoted string is a path, whatever it holds).
            Kind::Landmarks if decoded.is_none() && t.starts_with('{') => {
                serde_json::from_str::<Value>(t)
                    .ok()
                    .filter(Value::is_object)
            }
            Kind::Path | Kind::Landmarks => Some(Value::String(t.to_owned())),
            Kind::OptNames if t == "null" || t.is_empty() => Some(Value::Null),
            Kind::Paths | Kind::OptNames => serde_json::from_str::<Vec<String>>(t)
                .ok()
                .or_else(|| Some(t.split(',').map(|s| s.trim().to_owned()).collect()))
                .map(|v| v.into_iter().map(Value::String).collect()),
        };
        let value = value.ok_or_else(bad)?;
        match self.range_problem(&value) {
            Some(p) => Err(p),
            None => Ok(value),
        }
    }
}

/// A value quoted for a message, cut to a readable length.
fn quote(v: &Value) -> String {
    crate::base::limits::shorten(&v.to_string(), 60)
}

/// Type errors of every field present in `doc` (a parsed, shape-checked document), and
/// bad names and colours (which the typed parse would report without their path).
/// Returns the fields at fault.
pub(crate) fn check_types(doc: &Value, out: &mut Vec<String>) -> Vec<&'static Field> {
    let mut bad = Vec::new();
    for field in FIELDS.iter() {
        let Some(v) = get_path(doc, field.path) else {
            continue;
        };
        if !field.type_ok(v) {
            out.push(format!(
                "{}: expected {}, found {} {}",
                field.path,
                field.type_text(),
                type_name(v),
                quote(v)
            ));
            bad.push(field);
        } else if matches!(
            field.kind,
            Kind::Choice(_) | Kind::Colour | Kind::OptChoice(_) | Kind::OptColour
        ) && let Some(p) = field.range_problem(v)
        {
            out.push(p);
            bad.push(field);
        }
    }
    bad
}

/// Range errors of every field of a whole project document.
pub(crate) fn check_ranges(doc: &Value, out: &mut Vec<String>) {
    for field in FIELDS.iter().filter(|f| f.path != "version") {
        if let Some(v) = get_path(doc, field.path)
            && let Some(p) = field.range_problem(v)
        {
            out.push(p);
        }
    }
}

/// A default value as the docs show it.
fn default_text(v: &Value) -> String {
    match v {
        Value::Null => "null".into(),
        Value::String(s) => format!("`{s}`"),
        Value::Array(a) if a.is_empty() => "[]".into(),
        // The fields are f32: their shortest f32 text (0.35, not 0.3499999940395355).
        Value::Number(n) if n.is_f64() => n.as_f64().map_or(n.to_string(), |f| {
            let text = (f as f32).to_string();
            if text.contains('.') {
                text
            } else {
                format!("{text}.0")
            }
        }),
        other => other.to_string(),
    }
}

/// The docs page `docs/project-file.md`, generated from [`FIELDS`].
pub fn markdown() -> String {
    use std::fmt::Write as _;
    let mut out = String::from(include_str!("../project-file-intro.md"));
    for (section, about) in SECTIONS {
        let title = if section.is_empty() {
            "top level"
        } else {
            section
        };
        let _ = write!(out, "\n## `{title}`\n\n{about}\n\n");
        out.push_str("| field | unit | range | default | meaning |\n|---|---|---|---|---|\n");
        for field in FIELDS.iter().filter(|f| match f.path.split_once('.') {
            Some((s, _)) => s == *section,
            None => section.is_empty(),
        }) {
            let _ = writeln!(
                out,
                "| `{}` | {} | {} | {} | {} |",
                field.path,
                if field.unit.is_empty() {
                    "—"
                } else {
                    field.unit
                },
                field.range_text(),
                default_text(&field.default_value()),
                field.doc
            );
        }
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Every leaf of the default project, by path.
    fn leaves(v: &Value, at: &str, out: &mut Vec<String>) {
        match v {
            Value::Object(m) => {
                for (k, c) in m {
                    leaves(c, &super::super::json::join(at, k), out);
                }
            }
            _ => out.push(at.to_owned()),
        }
    }

    #[test]
    fn every_age_curve_of_the_project_is_listed_with_its_value() {
        let mut p = Project::default();
        p.age.pale.onset_years = 41.0;
        let rows = age_curves(&p);
        let paths: Vec<&str> = rows.iter().map(|r| r.path).collect();
        assert_eq!(
            paths,
            [
                "age.large",
                "age.fine",
                "age.pores",
                "age.furrows",
                "age.pale",
                "age.spots",
                "age.mottle",
                "age.redness",
                "age.contrast"
            ]
        );
        assert_eq!(rows[4].curve, p.age.pale);
        assert_eq!(rows[0].what, "large-wrinkle depth");
    }

    #[test]
    fn the_table_covers_every_field_of_the_project_exactly_once() {
        let mut paths = Vec::new();
        leaves(&super::super::Project::default().to_value(), "", &mut paths);
        let table: Vec<&str> = FIELDS.iter().map(|f| f.path).collect();
        for p in &paths {
            assert_eq!(
                table.iter().filter(|t| *t == p).count(),
                1,
                "{p} must be in the table once"
            );
        }
        assert_eq!(
            paths.len(),
            table.len(),
            "table has fields the project lacks"
        );
    }

    #[test]
    fn every_default_is_valid_for_its_own_field() {
        for field in FIELDS.iter() {
            let v = field.default_value();
            assert!(field.type_ok(&v), "{}: {v}", field.path);
            assert_eq!(field.range_problem(&v), None, "{}", field.path);
        }
    }

    #[test]
    fn every_choice_name_deserialises() {
        for field in FIELDS.iter() {
            if let Kind::Choice(names) = field.kind {
                for name in names {
                    let p = super::super::Project::default()
                        .set(field.path, name)
                        .unwrap_or_else(|e| panic!("{}={name}: {e}", field.path));
                    assert_eq!(
                        get_path(&p.to_value(), field.path),
                        Some(&Value::String(name.to_string()))
                    );
                }
            }
        }
    }

    #[test]
    fn the_docs_page_is_generated_from_the_table_and_up_to_date() {
        let path =
            std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("../../docs/project-file.md");
        let want = markdown();
        if std::env::var_os("UPDATE_DOCS").is_some() {
            std::fs::write(&path, &want).unwrap();
        }
        let have = std::fs::read_to_string(&path).unwrap_or_default();
        assert!(
            have == want,
            "docs/project-file.md is stale: run `UPDATE_DOCS=1 cargo test -p agesim-core the_docs_page` and commit it"
        );
        for field in FIELDS.iter() {
            assert!(
                want.contains(&format!("`{}`", field.path)),
                "{}",
                field.path
            );
        }
    }
}
