//! The fibre inspector: the selected fibre's parameters, and adding or deleting fibres.

use super::EditorApp;

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
        ui.horizontal(|ui| {
            if ui.button("Add fibre").clicked() {
                self.add_fibre();
            }
            let selected = self.persisted.map_view.selected.is_some();
            if ui
                .add_enabled(selected, egui::Button::new("Delete fibre"))
                .clicked()
                || (selected && ui.input(|i| i.key_pressed(egui::Key::Delete)))
            {
                self.delete_fibre();
            }
        });
        let Some((fi, gi)) = self.persisted.map_view.selected else {
            ui.label("Click a fibre's handle on the map to select it.");
            return;
        };
        let mut wrinkles = self.wrinkles().to_vec();
        if wrinkles
            .get(fi)
            .and_then(|w| w.file.groups.get(gi))
            .is_none()
        {
            return;
        }
        ui.label(format!("{} — group {}", wrinkles[fi].name, gi + 1));
        let group = &mut wrinkles[fi].file.groups[gi];
        let f = group.fibre.clone();
        let mut changed = None;
        ui.label(format!(
            "mA {:.3}; {:.3}   mB {:.3}; {:.3}",
            f.ma()[0],
            f.ma()[1],
            f.mb()[0],
            f.mb()[1]
        ));
        // Every slider takes its range from the fibre's one table (docs/models.md §2).
        use agesim_core::layers::wrinkles::fibre_params as params;
        use agesim_core::layers::wrinkles::muscle::Fibre;
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
                for p in agesim_core::layers::wrinkles::muscle::Profile::ALL {
                    ui.selectable_value(&mut profile, p, p.name());
                }
            });
        if profile != f.profile() {
            changed = Some(f.clone().with_profile(profile));
        }
        let mut own = group.age.is_some();
        let mut age_changed = false;
        if ui.checkbox(&mut own, "own age curve").changed() {
            group.age = own.then_some(self.doc.project.age.large);
            age_changed = true;
        }
        if let Some(curve) = &mut group.age {
            age_changed |= ui
                .add(
                    egui::Slider::new(&mut curve.onset_years, 0.0..=100.0)
                        .text("age onset (years)"),
                )
                .changed();
            age_changed |= ui
                .add(egui::Slider::new(&mut curve.full_years, 0.0..=120.0).text("age full (years)"))
                .changed();
            curve.full_years = curve.full_years.max(curve.onset_years);
        }
        if let Some(fibre) = changed {
            group.fibre = fibre;
            age_changed = true;
        }
        if age_changed {
            let dragging = ui.ctx().egui_is_using_pointer();
            self.record("fibre edit", &format!("fibre {fi}/{gi}"), dragging);
            self.doc.wrinkles = Some(wrinkles);
            self.submit(dragging, "fibre");
        }
    }
}
