//! The fibre inspector: the selected fibre's parameters, and adding or deleting fibres.

use super::EditorApp;
use super::command::Command;

impl EditorApp {
    /// Adds a fibre (3 creases across the middle of the UV square, irregular as the shipped
    /// layout's) to the selected fibre's file, or the first file, and selects it.
    pub fn add_fibre(&mut self) {
        let mut wrinkles = self.wrinkles().to_vec();
        let fi = self.persisted.map_view.selected.map_or(0, |(f, _)| f);
        let Ok(fibre) =
            agesim_core::layers::wrinkles::muscle::Fibre::new([0.45, 0.5], [0.55, 0.5], 3)
                .and_then(|f| f.with_irregularity(0.5))
                .and_then(|f| f.with_waviness(0.08))
                .map(|f| f.with_profile(agesim_core::layers::wrinkles::muscle::Profile::Crease))
        else {
            return;
        };
        let Some(file) = wrinkles.get_mut(fi) else {
            return;
        };
        file.file
            .groups
            .push(agesim_core::layers::wrinkles::wrinkle_file::WrinkleGroup {
                fibre,
                age: None,
                comments: vec![" added in the editor".into()],
            });
        self.persisted.map_view.selected = Some((fi, file.file.groups.len() - 1));
        self.record("add fibre", "add fibre", false);
        self.doc.wrinkles = Some(wrinkles);
        self.submit(false, "add fibre");
    }

    /// Deletes the selected fibre.
    pub fn delete_fibre(&mut self) {
        let Some((fi, gi)) = self.persisted.map_view.selected else {
            return;
        };
        let mut wrinkles = self.wrinkles().to_vec();
        if let Some(file) = wrinkles.get_mut(fi)
            && gi < file.file.groups.len()
        {
            file.file.groups.remove(gi);
            self.persisted.map_view.selected = None;
            self.record("delete fibre", "delete fibre", false);
            self.doc.wrinkles = Some(wrinkles);
            self.submit(false, "delete fibre");
        }
    }

    pub(super) fn inspector_ui(&mut self, ui: &mut egui::Ui) {
        let selected = self.persisted.map_view.selected;
        let mut wrinkles = self.wrinkles().to_vec();
        let group = match selected {
            Some((fi, gi)) => wrinkles.get_mut(fi).and_then(|w| {
                let title = format!("{} — group {}", w.name, gi + 1);
                w.file.groups.get_mut(gi).map(|g| (title, g))
            }),
            None => None,
        };
        let outcome = match group {
            Some((title, group)) => fibre_panel(ui, &title, group, self.doc.project.age.large),
            None => {
                let action = fibre_buttons(ui, false);
                if action.is_none() {
                    ui.label("Click a fibre's handle on the map to select it.");
                }
                Outcome {
                    action,
                    edited: false,
                }
            }
        };
        match outcome.action {
            Some(command) => self.run(command, &ui.ctx().clone()),
            None if outcome.edited => {
                let (fi, gi) = selected.unwrap_or_default();
                let dragging = ui.ctx().egui_is_using_pointer();
                self.record("fibre edit", &format!("fibre {fi}/{gi}"), dragging);
                self.doc.wrinkles = Some(wrinkles);
                self.submit(dragging, "fibre");
            }
            None => {}
        }
    }
}

/// What the fibre panel did: a button, or an edit of the group it was given.
struct Outcome {
    action: Option<Command>,
    edited: bool,
}

/// Add and Delete (Delete, and the Delete key, only with a fibre `selected`).
fn fibre_buttons(ui: &mut egui::Ui, selected: bool) -> Option<Command> {
    let mut action = None;
    ui.horizontal(|ui| {
        if ui.button("Add fibre").clicked() {
            action = Some(Command::AddFibre);
        }
        if ui
            .add_enabled(selected, egui::Button::new("Delete fibre"))
            .clicked()
            || (selected && ui.input(|i| i.key_pressed(egui::Key::Delete)))
        {
            action = Some(Command::DeleteFibre);
        }
    });
    action
}

/// The selected fibre's panel over the one `group` it edits: its parameters (each slider's
/// range from the fibre's one table, docs/models.md §2), profile and own age curve
/// (`layer_curve` when it takes one).
fn fibre_panel(
    ui: &mut egui::Ui,
    title: &str,
    group: &mut agesim_core::layers::wrinkles::wrinkle_file::WrinkleGroup,
    layer_curve: agesim_core::age::AgeCurve,
) -> Outcome {
    use agesim_core::layers::wrinkles::fibre_params as params;
    use agesim_core::layers::wrinkles::muscle::{Fibre, Profile};
    let action = fibre_buttons(ui, true);
    ui.label(title);
    let f = group.fibre.clone();
    let mut changed = None;
    ui.label(format!(
        "mA {:.3}; {:.3}   mB {:.3}; {:.3}",
        f.ma()[0],
        f.ma()[1],
        f.mb()[0],
        f.mb()[1]
    ));
    let mut n = f.n();
    let n_range = params::N.min as u32..=params::N.max as u32;
    if ui
        .add(
            egui::Slider::new(&mut n, n_range)
                .logarithmic(params::N.wide)
                .text("n (wrinkles)"),
        )
        .changed()
    {
        changed = f.with_n(n).ok();
    }
    type Setter = fn(Fibre, f32) -> Result<Fibre, agesim_core::Error>;
    let rows: [(params::FibreParam, f32, Setter); 6] = [
        (params::REL_WIDTH, f.rel_width(), Fibre::with_rel_width),
        (params::MAX_ANGLE, f.max_angle(), Fibre::with_max_angle),
        (params::OMEGA_LOW, f.omega_low(), Fibre::with_omega_low),
        (params::DEPTH, f.depth(), Fibre::with_depth),
        (
            params::IRREGULARITY,
            f.irregularity(),
            Fibre::with_irregularity,
        ),
        (params::WAVINESS, f.waviness(), Fibre::with_waviness),
    ];
    for (param, mut value, set) in rows {
        if ui
            .add(
                egui::Slider::new(&mut value, param.range())
                    .logarithmic(param.wide)
                    .text(param.key),
            )
            .changed()
        {
            changed = set(f.clone(), value).ok();
        }
    }
    let mut profile = f.profile();
    egui::ComboBox::from_label("profile")
        .selected_text(profile.name())
        .show_ui(ui, |ui| {
            for p in Profile::ALL {
                ui.selectable_value(&mut profile, p, p.name());
            }
        });
    if profile != f.profile() {
        changed = Some(f.clone().with_profile(profile));
    }
    let mut own = group.age.is_some();
    let mut edited = false;
    if ui.checkbox(&mut own, "own age curve").changed() {
        group.age = own.then_some(layer_curve);
        edited = true;
    }
    if let Some(curve) = &mut group.age {
        // The wrinkle file's `ageOnset`/`ageFull` range.
        let (lo, hi) = agesim_core::age::YEARS_RANGE;
        edited |= ui
            .add(egui::Slider::new(&mut curve.onset_years, lo..=hi).text("age onset (years)"))
            .changed();
        edited |= ui
            .add(egui::Slider::new(&mut curve.full_years, lo..=hi).text("age full (years)"))
            .changed();
        curve.full_years = curve.full_years.max(curve.onset_years);
    }
    if let Some(fibre) = changed {
        group.fibre = fibre;
        edited = true;
    }
    Outcome { action, edited }
}
