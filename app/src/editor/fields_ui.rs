//! The layer panel's widgets, made from the engine's field table
//! (`agesim_core::project::fields::FIELDS`): ranges, units, defaults and tooltips come from
//! there, not from a second copy here. Double-click a widget to reset it to its default;
//! a `•` marks values changed from the default.

use agesim_core::project::Project;
use agesim_core::project::fields::{FIELDS, Field, Kind, SECTIONS};
use serde_json::Value;

/// What the panel asks the app to do.
pub struct Edit {
    pub path: &'static str,
    pub value: Value,
    /// Whether the pointer is still dragging (bake a preview now, the full size later).
    pub dragging: bool,
    /// A path field's Load… / Add… button: open a file dialog for it (`value` unused).
    pub pick: Option<Pick>,
}

/// Which button of a path field was clicked.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Pick {
    /// Load… : replace the file(s).
    Replace,
    /// Add… : one more file (the wrinkle files).
    Add,
}

/// Sections shown as layers, with an on/off switch where the section has `enabled`.
pub const LAYER_SECTIONS: &[&str] = &[
    "large", "pores", "furrows", "noise", "warp", "overlap", "fine", "hair", "skin", "shape",
    "age", "normal", "view", "mesh", "",
];

/// A readable label: the path below the section, `_` as spaces.
fn label(field: &Field) -> String {
    let rest = field
        .path
        .split_once('.')
        .map_or(field.path, |(_, rest)| rest);
    rest.replace(['_', '.'], " ")
}

fn tooltip(field: &Field, default: &Value) -> String {
    let unit = if field.unit.is_empty() {
        String::new()
    } else {
        format!(" ({})", field.unit)
    };
    // Numbers are f32 in the project: show 0.4, not the f64 widening 0.4000000059604645.
    let default = match default.as_f64() {
        Some(x) if default.is_f64() => (x as f32).to_string(),
        _ => default.to_string(),
    };
    format!(
        "{}{unit}\nrange: {}\ndefault: {default}\n`{}` — double-click to reset",
        field.doc,
        field.range_text(),
        field.path
    )
}

/// The whole layer panel for `project` (changes marked against `defaults`; `wrinkles`:
/// the names of the wrinkle files being edited, shown instead of the project's paths;
/// `automatic(path)`: what a field left `null` stands for on this head — the mesh's
/// measured units, the hair and brow colours measured on it, the guessed hair loss — shown
/// and switched on with). Each field is read on its own ([`Project::field`]). Returns the
/// edits of this frame.
pub fn layers_ui(
    ui: &mut egui::Ui,
    project: &Project,
    defaults: &Project,
    wrinkles: Option<&[&str]>,
    automatic: &dyn Fn(&str) -> Option<Value>,
) -> Vec<Edit> {
    let value = |path: &str| match (path, wrinkles) {
        ("large.wrinkles", Some(names)) => Value::from(names.to_vec()),
        _ => project.field(path).unwrap_or(Value::Null),
    };
    let mut edits = Vec::new();
    for section in LAYER_SECTIONS {
        let about = SECTIONS
            .iter()
            .find(|(s, _)| s == section)
            .map_or("", |(_, a)| *a);
        let title = if section.is_empty() {
            "seed & patch"
        } else {
            section
        };
        let fields: Vec<&Field> = FIELDS
            .iter()
            .filter(|f| f.path != "version")
            .filter(|f| match f.path.split_once('.') {
                Some((s, _)) => s == *section,
                None => section.is_empty(),
            })
            .collect();
        let enabled_path = format!("{section}.enabled");
        let enabled = project.field(&enabled_path).and_then(|v| v.as_bool());
        let changed_count = fields
            .iter()
            .filter(|f| value(f.path) != defaults.field(f.path).unwrap_or(Value::Null))
            .count();
        let header = if changed_count > 0 {
            format!("{title}  • {changed_count}")
        } else {
            title.to_owned()
        };
        egui::CollapsingHeader::new(header)
            .id_salt(("layer", *section))
            .default_open(matches!(*section, "large" | "age"))
            .show(ui, |ui| {
                ui.label(egui::RichText::new(about).weak().small());
                if let Some(on) = enabled {
                    let mut v = on;
                    if ui.checkbox(&mut v, "enabled").changed() {
                        edits.push(Edit {
                            path: FIELDS
                                .iter()
                                .find(|f| f.path == enabled_path)
                                .map_or("", |f| f.path),
                            value: Value::Bool(v),
                            dragging: false,
                            pick: None,
                        });
                    }
                }
                ui.add_enabled_ui(enabled != Some(false), |ui| {
                    egui::Grid::new(("fields", *section))
                        .num_columns(2)
                        .striped(true)
                        .show(ui, |ui| {
                            for field in fields.iter().filter(|f| !f.path.ends_with(".enabled")) {
                                let value = value(field.path);
                                let default = defaults.field(field.path).unwrap_or(Value::Null);
                                let measured = automatic(field.path);
                                if let Some(edit) =
                                    field_ui(ui, field, &value, &default, measured.as_ref())
                                {
                                    edits.push(edit);
                                }
                                ui.end_row();
                            }
                        });
                });
            });
    }
    edits
}

/// The on/off box of an optional field (off = `null`, automatic).
fn auto_toggle(ui: &mut egui::Ui, is_null: bool, when_on: Value, out: &mut Option<(Value, bool)>) {
    let mut on = !is_null;
    if ui
        .checkbox(&mut on, "")
        .on_hover_text("off = automatic")
        .changed()
    {
        *out = Some((if on { when_on } else { Value::Null }, false));
    }
}

/// One field: a label (marked when changed) and its widget.
fn field_ui(
    ui: &mut egui::Ui,
    field: &'static Field,
    value: &Value,
    default: &Value,
    measured: Option<&Value>,
) -> Option<Edit> {
    let tip = tooltip(field, default);
    let label_id = ui
        .horizontal(|ui| {
            if value != default {
                ui.label(egui::RichText::new("•").color(egui::Color32::from_rgb(255, 200, 60)))
                    .on_hover_text("changed from the default");
            }
            ui.label(label(field)).on_hover_text(&tip).id
        })
        .inner;
    let mut out: Option<(Value, bool)> = None;
    let mut pick = None;
    let response = match field.kind {
        Kind::Float { min, max } | Kind::OptFloat { min, max } => {
            let is_null = value.is_null();
            // Off (`null`): the value shown and switched on with — the measured one where
            // there is one (the mesh's units), else the default, else 1 where the range
            // allows (not the range's minimum: 0.00001 m per unit shrinks a head to a speck).
            let mut x = value
                .as_f64()
                .or(measured.and_then(Value::as_f64))
                .or(default.as_f64())
                .unwrap_or_else(|| 1f64.clamp(f64::from(min), f64::from(max)));
            let r = ui
                .horizontal(|ui| {
                    if matches!(field.kind, Kind::OptFloat { .. }) {
                        auto_toggle(ui, is_null, Value::from(x), &mut out);
                    }
                    // Logarithmic over three decades or more of positive values (a size
                    // in metres per unit), or from 0 to beyond 1000 (a count); a 0–1
                    // strength is linear, as artists' sliders are (a log slider put most of
                    // its track below 0.01 and showed 0 as "0.000000").
                    let log = (min > 0.0 && max / min > 1000.0) || (min == 0.0 && max > 1000.0);
                    let r = ui.add_enabled(
                        !is_null,
                        egui::Slider::new(&mut x, min as f64..=max as f64)
                            .logarithmic(log)
                            .clamping(egui::SliderClamping::Always),
                    );
                    if r.changed() {
                        out = Some((Value::from(x), r.dragged()));
                    }
                    if r.drag_stopped() && out.is_none() {
                        out = Some((Value::from(x), false));
                    }
                    if is_null && measured.is_some() {
                        ui.label(
                            egui::RichText::new(automatic_word(field.path))
                                .weak()
                                .small(),
                        );
                    }
                    r
                })
                .inner;
            Some(r)
        }
        Kind::Int { min, max } | Kind::OptInt { min, max } => {
            let is_null = value.is_null();
            let mut x = value.as_u64().unwrap_or(min);
            let r = ui
                .horizontal(|ui| {
                    if matches!(field.kind, Kind::OptInt { .. }) {
                        auto_toggle(ui, is_null, Value::from(x), &mut out);
                    }
                    let r = if max - min <= 100_000 {
                        ui.add_enabled(
                            !is_null,
                            egui::Slider::new(&mut x, min..=max).logarithmic(max - min > 1000),
                        )
                    } else {
                        ui.add_enabled(!is_null, egui::DragValue::new(&mut x).range(min..=max))
                    };
                    if r.changed() {
                        out = Some((Value::from(x), r.dragged()));
                    }
                    r
                })
                .inner;
            Some(r)
        }
        Kind::Bool => {
            let mut b = value.as_bool().unwrap_or(false);
            let r = ui.checkbox(&mut b, "");
            if r.changed() {
                out = Some((Value::Bool(b), false));
            }
            Some(r)
        }
        Kind::Choice(names) => {
            let current = value.as_str().unwrap_or("").to_owned();
            let mut selected = current.clone();
            let r = egui::ComboBox::from_id_salt(field.path)
                .selected_text(&selected)
                .show_ui(ui, |ui| {
                    for n in names {
                        ui.selectable_value(&mut selected, n.to_string(), *n);
                    }
                })
                .response;
            if selected != current {
                out = Some((Value::String(selected), false));
            }
            Some(r)
        }
        Kind::Colour => {
            let mut rgb = value
                .as_str()
                .and_then(agesim_core::project::Colour::parse)
                .map_or([0, 0, 0], |c| c.0);
            let r = ui.color_edit_button_srgb(&mut rgb);
            if r.changed() {
                let c = agesim_core::project::Colour(rgb);
                out = Some((Value::String(c.to_string()), false));
            }
            Some(r)
        }
        Kind::OptColour => {
            // Off (`null`): measured on the head; shown, and switched on with.
            let is_null = value.is_null();
            let shown = if is_null { measured } else { Some(value) };
            let mut rgb = shown
                .and_then(Value::as_str)
                .and_then(agesim_core::project::Colour::parse)
                .map_or([0, 0, 0], |c| c.0);
            let r = ui
                .horizontal(|ui| {
                    let on_with = Value::String(agesim_core::project::Colour(rgb).to_string());
                    auto_toggle(ui, is_null, on_with, &mut out);
                    let r = ui.add_enabled_ui(!is_null, |ui| ui.color_edit_button_srgb(&mut rgb));
                    if r.inner.changed() {
                        let c = agesim_core::project::Colour(rgb);
                        out = Some((Value::String(c.to_string()), false));
                    }
                    if is_null {
                        ui.label(egui::RichText::new("measured").weak().small());
                    }
                    r.inner
                })
                .inner;
            Some(r)
        }
        Kind::OptChoice(names) => {
            // Off (`null`): guessed from the head; shown, and switched on with.
            let is_null = value.is_null();
            let shown = if is_null { measured } else { Some(value) };
            let current = shown.and_then(Value::as_str).unwrap_or(names[0]).to_owned();
            let mut selected = current.clone();
            let r = ui
                .horizontal(|ui| {
                    auto_toggle(ui, is_null, Value::String(current.clone()), &mut out);
                    let r = ui.add_enabled_ui(!is_null, |ui| {
                        egui::ComboBox::from_id_salt(field.path)
                            .selected_text(&selected)
                            .show_ui(ui, |ui| {
                                for n in names {
                                    ui.selectable_value(&mut selected, n.to_string(), *n);
                                }
                            })
                            .response
                    });
                    if is_null {
                        ui.label(egui::RichText::new("guessed").weak().small());
                    }
                    r.inner
                })
                .inner;
            if selected != current {
                out = Some((Value::String(selected), false));
            }
            Some(r)
        }
        Kind::OptNames => {
            // Typed as a comma-separated list; taken when the field loses focus.
            let current = value.as_array().map_or(String::new(), |a| {
                a.iter()
                    .filter_map(Value::as_str)
                    .collect::<Vec<_>>()
                    .join(", ")
            });
            let id = ui.scope_id().with(("names field", field.path));
            let mut text = ui
                .data_mut(|d| d.get_temp::<String>(id))
                .unwrap_or_else(|| current.clone());
            let r = ui.add(
                egui::TextEdit::singleline(&mut text)
                    .hint_text("automatic")
                    .desired_width(150.0),
            );
            if r.changed() {
                ui.data_mut(|d| d.insert_temp(id, text.clone()));
            }
            if r.lost_focus() {
                ui.data_mut(|d| d.remove::<String>(id));
                if text.trim() != current
                    && let Ok(v) = field.parse_text(&text)
                {
                    out = Some((v, false));
                }
            }
            Some(r)
        }
        Kind::Path | Kind::Paths | Kind::Landmarks => {
            let text = match value {
                Value::Null if field.kind == Kind::Landmarks => "(none)".to_owned(),
                Value::Null => "(built-in)".to_owned(),
                Value::Object(points) => format!("{} points in the project", points.len()),
                Value::Array(a) if a.is_empty() => "(built-in)".to_owned(),
                Value::Array(a) => format!("{} files", a.len()),
                other => other.as_str().unwrap_or("").to_owned(),
            };
            // The file name only: the whole path is in the tooltip.
            let short = std::path::Path::new(&text)
                .file_name()
                .map_or_else(|| text.clone(), |n| n.to_string_lossy().into_owned());
            let r = ui
                .horizontal(|ui| {
                    let r = ui
                        .label(egui::RichText::new(short).monospace())
                        .on_hover_text(&text);
                    if ui.small_button("Load…").clicked() {
                        pick = Some(Pick::Replace);
                    }
                    if matches!(field.kind, Kind::Paths) && ui.small_button("Add…").clicked() {
                        pick = Some(Pick::Add);
                    }
                    r
                })
                .inner;
            Some(r)
        }
    };
    if pick.is_some() {
        return Some(Edit {
            path: field.path,
            value: Value::Null,
            dragging: false,
            pick,
        });
    }
    if let Some(r) = response {
        // Screen readers and tests find the widget by its field name.
        let r = r.on_hover_text(&tip).labelled_by(label_id);
        if r.double_clicked() && value != default {
            out = Some((default.clone(), false));
        }
    }
    out.map(|(value, dragging)| Edit {
        path: field.path,
        value,
        dragging,
        pick: None,
    })
}

/// How the value a `null` number shows came about: measured on the head (its units), or
/// guessed from it (the hair's curl, from the skin's tone).
fn automatic_word(path: &str) -> &'static str {
    if path == "mesh.metres_per_unit" {
        "measured"
    } else {
        "guessed"
    }
}
