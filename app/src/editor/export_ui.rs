//! The Export window: maps, renders and the aged head (GLB) at a chosen age, written by
//! [`crate::export`] on a thread of its own with a progress bar and Cancel. Cancelling
//! leaves no file (the output set is all old or all new).

use std::path::PathBuf;
use std::sync::mpsc::{Receiver, channel};
use std::sync::{Arc, Mutex};

use agesim_core::base::cancel::CancelToken;
use agesim_core::maps::normal_map::Convention;
use agesim_core::output::names::{MapKind, Naming};
use agesim_core::project::Project;
use agesim_core::scene::WrinkleSource;

use crate::export::{ExportRequest, GlbHair, GlbOut, MapsOut, RendersOut};

/// The window's choices, kept between runs.
#[derive(Clone, Debug, serde::Serialize, serde::Deserialize)]
#[serde(default)]
pub struct ExportSettings {
    pub folder: Option<PathBuf>,
    /// File names start with this (the texture set's name): `head_Height.png`,
    /// `head.glb`, ….
    pub base: String,
    /// How the maps are named: `head_BaseColor.png`, … (texture set) or `head_albedo.png`,
    /// … (agesim's names).
    pub names: Naming,
    /// Export at the timeline's age (else at `years`).
    pub at_current_age: bool,
    pub years: f32,
    pub size_px: u32,
    pub height_png: bool,
    pub height_exr: bool,
    pub exr_compression: agesim_core::output::export::ExrCompression,
    pub normal_png: bool,
    pub base_colour_png: bool,
    pub roughness_png: bool,
    pub ao_png: bool,
    pub directx: bool,
    pub tileable: bool,
    pub glb: bool,
    /// How much of the hair the GLB carries.
    pub glb_hair: GlbHair,
    pub render: bool,
    pub sequence: bool,
    /// Ages of the sequence, years, comma separated.
    pub sequence_years: String,
    pub compare: bool,
    pub compare_years: [f32; 2],
    pub render_px: [u32; 2],
}

impl Default for ExportSettings {
    fn default() -> Self {
        Self {
            folder: None,
            base: "head".into(),
            names: Naming::TextureSet,
            at_current_age: true,
            years: 70.0,
            size_px: 2048,
            height_png: true,
            height_exr: false,
            exr_compression: agesim_core::output::export::ExrCompression::Rle,
            normal_png: true,
            base_colour_png: true,
            roughness_png: true,
            ao_png: true,
            directx: false,
            tileable: false,
            glb: true,
            glb_hair: GlbHair::Light,
            render: false,
            sequence: false,
            sequence_years: "25, 40, 55, 70, 85".into(),
            compare: false,
            compare_years: [25.0, 75.0],
            render_px: [1024, 1024],
        }
    }
}

/// Map sizes offered (8192² needs about 1 GiB while baking).
pub const SIZES: [u32; 5] = [512, 1024, 2048, 4096, 8192];

impl ExportSettings {
    /// The request for these settings at `years`, or why there is none.
    pub fn request(&self, years: f32) -> Result<ExportRequest, String> {
        let Some(folder) = &self.folder else {
            return Err("choose a folder to export into".into());
        };
        let base = self.base.trim();
        if base.is_empty() || base.contains(['/', '\\']) {
            return Err(format!(
                "`{base}` is not a file name: type a name without folders"
            ));
        }
        let file = |suffix: &str| folder.join(format!("{base}{suffix}"));
        let map =
            |on: bool, kind: MapKind| on.then(|| folder.join(kind.file_name(self.names, base)));
        let sequence = if self.sequence {
            let years: Result<Vec<f32>, _> = self
                .sequence_years
                .split(',')
                .map(|s| s.trim().parse::<f32>())
                .collect();
            match years {
                Ok(y) if !y.is_empty() => Some((file("_age.png"), y)),
                _ => {
                    return Err(format!(
                        "sequence ages `{}`: expected years separated by commas, e.g. 30, 50, 70",
                        self.sequence_years
                    ));
                }
            }
        } else {
            None
        };
        Ok(ExportRequest {
            years,
            maps: MapsOut {
                size_px: self.size_px,
                height_png: map(self.height_png, MapKind::Height),
                height_exr: map(self.height_exr, MapKind::HeightExr),
                normal_png: map(self.normal_png, MapKind::Normal),
                base_colour_png: map(self.base_colour_png, MapKind::BaseColour),
                roughness_png: map(self.roughness_png, MapKind::Roughness),
                ao_png: map(self.ao_png, MapKind::Ao),
                convention: Some(if self.directx {
                    Convention::DirectX
                } else {
                    Convention::OpenGl
                }),
                tileable: self.tileable,
                exr_compression: self.exr_compression,
            },
            glb: self.glb.then(|| GlbOut {
                hair: self.glb_hair,
                path: file(".glb"),
                size_px: self.size_px,
            }),
            renders: RendersOut {
                size: (self.render_px[0], self.render_px[1]),
                image: self.render.then(|| file("_render.png")),
                sequence,
                compare: self
                    .compare
                    .then(|| (file("_compare.png"), self.compare_years)),
            },
        })
    }
}

/// An export running on its thread.
pub struct ExportRun {
    cancel: CancelToken,
    progress: Arc<Mutex<(f32, String)>>,
    done: Receiver<Result<Vec<PathBuf>, String>>,
}

impl ExportRun {
    pub fn start(
        project: Project,
        wrinkles: Option<Vec<WrinkleSource>>,
        request: ExportRequest,
        wake: impl Fn() + Send + Sync + 'static,
    ) -> Self {
        let cancel = CancelToken::new();
        let progress = Arc::new(Mutex::new((0.0, "starting".to_owned())));
        let (tx, done) = channel();
        let (token, shared) = (cancel.clone(), progress.clone());
        let wake = Arc::new(wake);
        std::thread::spawn(move || {
            let report = |f: f32, what: &str| {
                *shared.lock().unwrap_or_else(|p| p.into_inner()) = (f, what.to_owned());
                wake();
            };
            let result =
                crate::export::run(&project, wrinkles.as_deref(), &request, &report, &token)
                    .map_err(|e| format!("{e:#}"));
            let _ = tx.send(result);
            wake();
        });
        Self {
            cancel,
            progress,
            done,
        }
    }

    pub fn cancel(&self) {
        self.cancel.cancel();
    }

    pub fn cancelled(&self) -> bool {
        self.cancel.is_cancelled()
    }

    pub fn progress(&self) -> (f32, String) {
        self.progress
            .lock()
            .unwrap_or_else(|p| p.into_inner())
            .clone()
    }

    /// The result, once the thread is done.
    pub fn finished(&self) -> Option<Result<Vec<PathBuf>, String>> {
        self.done.try_recv().ok()
    }
}

/// What the window asks the app to do.
#[derive(Debug, PartialEq, Eq)]
pub enum ExportAction {
    None,
    ChooseFolder,
    Start,
    Cancel,
}

/// About how many bytes a hair takes in the GLB (5 points × 2 vertices × 32 bytes, 4 quads
/// × 6 indices × 4 bytes).
const GLB_BYTES_PER_HAIR: f64 = 416.0;

/// The window's contents. `running`: the progress of a running export; `hairs`: the
/// hairs the view draws at its age (for the GLB's size).
pub fn export_ui(
    ui: &mut egui::Ui,
    s: &mut ExportSettings,
    current_years: f32,
    running: Option<(f32, String)>,
    hairs: u32,
) -> ExportAction {
    let mut action = ExportAction::None;
    ui.add_enabled_ui(running.is_none(), |ui| {
        egui::Grid::new("export grid")
            .num_columns(2)
            .spacing([12.0, 6.0])
            .show(ui, |ui| {
                let label = ui.label("Folder").id;
                ui.horizontal(|ui| {
                    // Typed or chosen: both are what artists expect.
                    let mut text = s
                        .folder
                        .as_ref()
                        .map_or_else(String::new, |f| f.display().to_string());
                    let r = ui
                        .add(
                            egui::TextEdit::singleline(&mut text)
                                .hint_text("type a folder or choose one")
                                .desired_width(280.0),
                        )
                        .labelled_by(label);
                    if r.changed() {
                        s.folder = (!text.is_empty()).then(|| PathBuf::from(text));
                    }
                    if ui.button("Choose…").clicked() {
                        action = ExportAction::ChooseFolder;
                    }
                });
                ui.end_row();
                let label = ui.label("Name").id;
                ui.text_edit_singleline(&mut s.base).labelled_by(label);
                ui.end_row();
                let label = ui.label("Age").id;
                ui.horizontal(|ui| {
                    ui.checkbox(
                        &mut s.at_current_age,
                        format!("timeline ({current_years:.0} years)"),
                    );
                    ui.add_enabled(
                        !s.at_current_age,
                        egui::DragValue::new(&mut s.years)
                            .range(0.0..=150.0)
                            .suffix(" years"),
                    )
                    .labelled_by(label);
                });
                ui.end_row();
                let label = ui.label("Map size").id;
                egui::ComboBox::from_id_salt("export size")
                    .selected_text(format!("{0} × {0}", s.size_px))
                    .show_ui(ui, |ui| {
                        for n in SIZES {
                            ui.selectable_value(&mut s.size_px, n, format!("{n} × {n}"));
                        }
                    })
                    .response
                    .labelled_by(label);
                ui.end_row();
                ui.label("Maps");
                ui.vertical(|ui| {
                    ui.checkbox(&mut s.height_png, "height, 16-bit PNG");
                    ui.horizontal(|ui| {
                        use agesim_core::output::export::ExrCompression as C;
                        ui.checkbox(&mut s.height_exr, "height, 32-bit float EXR");
                        for (c, name) in [(C::Rle, "RLE"), (C::None, "none"), (C::Zip, "ZIP")] {
                            ui.radio_value(&mut s.exr_compression, c, name);
                        }
                    });
                    ui.horizontal(|ui| {
                        ui.checkbox(&mut s.normal_png, "normal PNG");
                        ui.radio_value(&mut s.directx, false, "OpenGL");
                        ui.radio_value(&mut s.directx, true, "DirectX");
                    });
                    ui.horizontal(|ui| {
                        ui.checkbox(&mut s.base_colour_png, "base colour");
                        ui.checkbox(&mut s.roughness_png, "roughness");
                        ui.checkbox(&mut s.ao_png, "occlusion");
                    });
                    ui.checkbox(&mut s.tileable, "tileable (skin patch)");
                    ui.horizontal(|ui| {
                        let label = ui.label("names").id;
                        for (n, text) in [
                            (Naming::TextureSet, "texture set"),
                            (Naming::Agesim, "agesim"),
                        ] {
                            ui.radio_value(&mut s.names, n, text).labelled_by(label);
                        }
                        ui.weak(MapKind::Height.file_name(s.names, s.base.trim()));
                    });
                });
                ui.end_row();
                ui.label("Head");
                ui.vertical(|ui| {
                    ui.checkbox(
                        &mut s.glb,
                        "aged head as GLB (normal, base colour, roughness, occlusion; height map beside)",
                    );
                    ui.add_enabled_ui(s.glb, |ui| {
                        ui.horizontal(|ui| {
                            let label = ui.label("hair").id;
                            let mb = |stride: usize| {
                                f64::from(hairs) / stride as f64 * GLB_BYTES_PER_HAIR / 1e6
                            };
                            for (h, text) in [
                                (GlbHair::None, "none".to_owned()),
                                (GlbHair::Light, format!("light (≈ {:.0} MB)", mb(GlbHair::LIGHT_STRIDE))),
                                (GlbHair::Full, format!("full (≈ {:.0} MB)", mb(1))),
                            ] {
                                ui.radio_value(&mut s.glb_hair, h, text).labelled_by(label);
                            }
                        });
                    });
                });
                ui.end_row();
                ui.label("Renders");
                ui.vertical(|ui| {
                    ui.horizontal(|ui| {
                        let w = ui.label("width").id;
                        ui.add(egui::DragValue::new(&mut s.render_px[0]).range(64..=8192))
                            .labelled_by(w);
                        let h = ui.label("height").id;
                        ui.add(egui::DragValue::new(&mut s.render_px[1]).range(64..=8192))
                            .labelled_by(h);
                    });
                    ui.checkbox(&mut s.render, "image at the age");
                    ui.horizontal(|ui| {
                        let label = ui.checkbox(&mut s.sequence, "age sequence, years:").id;
                        ui.add_enabled(
                            s.sequence,
                            egui::TextEdit::singleline(&mut s.sequence_years).desired_width(140.0),
                        )
                        .labelled_by(label);
                    });
                    ui.horizontal(|ui| {
                        let label = ui.checkbox(&mut s.compare, "young | old comparison:").id;
                        for y in &mut s.compare_years {
                            ui.add_enabled(
                                s.compare,
                                egui::DragValue::new(y).range(0.0..=150.0).suffix(" y"),
                            )
                            .labelled_by(label);
                        }
                    });
                });
                ui.end_row();
            });
    });
    ui.separator();
    match running {
        Some((fraction, what)) => {
            ui.add(
                egui::ProgressBar::new(fraction)
                    .show_percentage()
                    .text(format!("{what} — {:.0} %", fraction * 100.0)),
            );
            if ui.button("Cancel").clicked() {
                action = ExportAction::Cancel;
            }
        }
        None => {
            if ui
                .add_enabled(s.folder.is_some(), egui::Button::new("Export"))
                .on_disabled_hover_text("choose a folder first")
                .clicked()
            {
                action = ExportAction::Start;
            }
        }
    }
    action
}
