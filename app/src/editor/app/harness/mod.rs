//! Scripted runs, kept out of the editor's own state: the UI benchmark (`--bench-ui`,
//! [`bench`]), the screenshot (`--screenshot`), the soak run (`--soak`, [`soak`]) and the
//! hidden `--edit`. The app holds one [`Harness`], empty in an artist's session; each frame
//! it calls the harness's steps, which drive the app through the calls its widgets make.

pub mod bench;
pub mod soak;

use std::path::PathBuf;

use agesim_core::project::fields::{FIELDS, Field, Kind};
use serde_json::Value;

use super::{EditorApp, EditorOptions, Layout};
use bench::BenchUi;
use soak::{Action, Soak};

/// What drives a scripted run; every part `None` in an artist's session.
#[derive(Default)]
pub(super) struct Harness {
    bench: Option<BenchUi>,
    soak: Option<SoakRun>,
    /// Frames drawn with maps before the screenshot, and whether it was asked for.
    frames_with_maps: u32,
    /// Whether the first frame with aged maps (perhaps a first look at the preview size)
    /// was reported.
    first_aged_reported: bool,
    screenshot_requested: bool,
}

impl Harness {
    /// The harness of `options`' scripted run.
    pub(super) fn for_options(options: &EditorOptions) -> Self {
        Self {
            bench: options.bench_ui.then(BenchUi::new),
            soak: options.soak_seconds.map(SoakRun::new),
            ..Self::default()
        }
    }

    /// Whether this frame paints nothing but an empty panel (the benchmark's floor).
    pub(super) fn floor(&self) -> bool {
        self.bench.as_ref().is_some_and(BenchUi::floor)
    }

    /// Whether a scripted drag is under way (the view draws as when moving).
    pub(super) fn dragging(&self) -> bool {
        self.bench.as_ref().is_some_and(BenchUi::dragging)
    }

    /// A message the app showed (the soak checks that only expected errors appear).
    pub(super) fn shown(&mut self, text: &str, error: bool) {
        if let Some(soak) = &mut self.soak {
            if error {
                soak.error_shown(text);
            } else {
                soak.info_shown(text);
            }
        }
    }
}

impl EditorApp {
    /// `--edit field=value`: applied once the first maps are shown, as the layer panel
    /// would (one undo step, the document modified).
    pub(super) fn scripted_edit(&mut self) {
        if self.session.snapshot.large.is_none() || self.autosave.offer.is_some() {
            return;
        }
        let Some(edit) = self.options.edit.take() else {
            return;
        };
        let Some((path, text)) = edit.split_once('=') else {
            self.error(format!("--edit {edit}: expected FIELD=VALUE"));
            return;
        };
        let Some(field) = agesim_core::project::fields::FIELDS
            .iter()
            .find(|f| f.path == path.trim())
        else {
            self.error(format!("--edit {edit}: no field {path}"));
            return;
        };
        match field.parse_text(text) {
            Ok(value) => self.apply(field.path, value, false),
            Err(e) => self.error(format!("--edit: {e}")),
        }
    }

    pub(super) fn bench_step(&mut self, ctx: &egui::Context) {
        let Some(bench) = &mut self.harness.bench else {
            return;
        };
        ctx.request_repaint();
        let hairs = self
            .viewport
            .as_ref()
            .map_or((0, 1), |v| (v.hairs_drawn, v.sparse_hair));
        let idle = !self.session.busy();
        let years = self.doc.project.age.mapping().years(self.doc.project.age.t);
        match bench.frame(
            idle,
            (self.session.reported, self.session.last_bake_ms),
            self.session.worker.latest,
            hairs,
            years,
            self.governor.quality().scale,
        ) {
            bench::Action::None => {}
            bench::Action::BigBake => self.submit_sized((4096, 4096), "4096² bake"),
            bench::Action::SetAge(t) => self.set_age(t, true),
            bench::Action::Drag(path, value) => {
                self.apply(path, Value::from(value), true);
            }
            bench::Action::Play => self.persisted.playback.playing = true,
            bench::Action::PlayHeadOnly => {
                self.persisted.layout = Layout::Head;
                self.persisted.playback.playing = true;
            }
            bench::Action::Stop => self.persisted.playback.playing = false,
            bench::Action::StopBoth => {
                self.persisted.playback.playing = false;
                self.persisted.layout = Layout::Both;
            }
            bench::Action::Quit => ctx.send_viewport_cmd(egui::ViewportCommand::Close),
        }
    }

    pub(super) fn maybe_screenshot(&mut self, ctx: &egui::Context) {
        let Some(path) = self.options.screenshot.clone() else {
            return;
        };
        let since_launch = || {
            self.options
                .launched
                .map_or(0.0, |l| l.elapsed().as_secs_f64())
        };
        if let Some(large) = &self.session.snapshot.large
            && !self.harness.first_aged_reported
        {
            self.harness.first_aged_reported = true;
            let px = large.height.width_px();
            println!(
                "first aged frame: {:.2} s after launch ({px}² maps)",
                since_launch()
            );
        }
        if self.session.snapshot.large.is_some() && self.idle() {
            if self.harness.frames_with_maps == 0 {
                println!("settled: {:.2} s after launch", since_launch());
            }
            self.harness.frames_with_maps += 1;
            ctx.request_repaint();
        } else {
            // Waiting for the bake: the worker wakes the window when it reports, and no
            // frame in between takes the cores from it.
            ctx.request_repaint_after(std::time::Duration::from_millis(250));
        }
        if self.harness.frames_with_maps >= self.options.frames.max(1)
            && !self.harness.screenshot_requested
        {
            self.harness.screenshot_requested = true;
            let ctx2 = ctx.clone();
            ctx.request_screenshot(move |image| {
                let [w, h] = image.size;
                let bytes: Vec<u8> = image.pixels.iter().flat_map(|c| c.to_array()).collect();
                let result = image::RgbaImage::from_raw(w as u32, h as u32, bytes)
                    .map(|img| img.save(&path));
                match result {
                    Some(Ok(())) => println!("screenshot {w}×{h} → {}", path.display()),
                    _ => eprintln!("error: could not write the screenshot {}", path.display()),
                }
                ctx2.send_viewport_cmd(egui::ViewportCommand::Close);
            });
        }
    }
}

/// The soak run's state on the app's side: the script ([`Soak`]), its folder and the
/// slider fields it drags.
struct SoakRun {
    soak: Soak,
    dir: PathBuf,
    fields: Vec<&'static Field>,
    /// The wrinkle file a rewrite left broken (its errors are expected).
    broken: String,
    /// A slider edit of the script is being applied (an error now is a refusal).
    in_edit: bool,
}

impl SoakRun {
    fn new(seconds: f64) -> Self {
        // Every number and switch of the layers and the view; not the mesh's (units,
        // axes: a different head) nor the age mapping (the scrubs move the age).
        let fields: Vec<&'static Field> = FIELDS
            .iter()
            .filter(|f| matches!(f.kind, Kind::Float { .. } | Kind::Bool))
            .filter(|f| !f.path.starts_with("mesh.") && !f.path.starts_with("age."))
            .collect();
        let dir = std::env::temp_dir().join(format!("agesim-soak-{}", std::process::id()));
        println!(
            "soak: {seconds:.0} s, seed 1, {} slider fields, files in {}",
            fields.len(),
            dir.display()
        );
        Self {
            soak: Soak::new(seconds, fields.len(), 1),
            dir,
            fields,
            broken: String::new(),
            in_edit: false,
        }
    }

    pub(super) fn info_shown(&mut self, text: &str) {
        self.soak.info_shown(text);
    }

    /// An error the app showed.
    pub(super) fn error_shown(&mut self, text: &str) {
        self.soak.error_shown(text, &self.broken, self.in_edit);
    }
}

impl EditorApp {
    pub(super) fn soak_step(&mut self, ctx: &egui::Context) {
        let Some(run) = &mut self.harness.soak else {
            return;
        };
        ctx.request_repaint();
        let ready = self.session.snapshot.large.is_some();
        let action = run
            .soak
            .frame(self.session.worker.latest, self.session.reported, ready);
        match action {
            Action::None => {}
            Action::Setup => {
                if let Err(e) = std::fs::create_dir_all(&run.dir) {
                    eprintln!("error: {}: {e}", run.dir.display());
                }
                let path = run.dir.join("soak.agesim.json");
                // The wrinkle files as edited, so the save writes them (and the mask)
                // into the folder: the files the script rewrites on disk.
                if self.doc.wrinkles.is_none() {
                    self.doc.wrinkles = Some(self.wrinkles().to_vec());
                }
                self.save_to(path);
            }
            Action::Field {
                field,
                fraction,
                dragging,
            } => {
                let Some(f) = run.fields.get(field).copied() else {
                    return;
                };
                let value = match f.kind {
                    Kind::Float { min, max } => Value::from(min + (max - min) * fraction),
                    _ => Value::from(fraction > 0.5),
                };
                run.in_edit = true;
                if !dragging && sizes_the_caches(f.path) {
                    run.soak.capacity_changed();
                }
                self.apply(f.path, value, dragging);
                if let Some(run) = &mut self.harness.soak {
                    run.in_edit = false;
                }
            }
            Action::Fibre {
                pick,
                delta,
                dragging,
            } => {
                let wrinkles = self.wrinkles().to_vec();
                let groups: Vec<(usize, usize)> = wrinkles
                    .iter()
                    .enumerate()
                    .flat_map(|(i, w)| (0..w.file.groups.len()).map(move |g| (i, g)))
                    .collect();
                let Some(&(file, group)) = groups.get((pick % groups.len().max(1) as u64) as usize)
                else {
                    return;
                };
                let f = &wrinkles[file].file.groups[group].fibre;
                let shift = |p: [f32; 2]| {
                    [
                        (p[0] + delta[0]).clamp(0.0, 1.0),
                        (p[1] + delta[1]).clamp(0.0, 1.0),
                    ]
                };
                if let Ok(fibre) = f.with_ends(shift(f.ma()), shift(f.mb())) {
                    let edit = crate::editor::map_view::FibreEdit {
                        file,
                        group,
                        fibre,
                        dragging,
                    };
                    self.apply_fibre_edit(wrinkles, edit);
                }
            }
            Action::Age { t, moving } => {
                if t != self.doc.project.age.t {
                    self.record("age", "age", moving);
                }
                self.set_age(t, moving);
            }
            Action::Undo => self.undo(),
            Action::Redo => self.redo(),
            Action::RewriteWrinkles { pick, broken } => {
                let paths: Vec<PathBuf> = self
                    .wrinkles()
                    .iter()
                    .filter_map(|w| w.path.clone())
                    .collect();
                let Some(path) = paths.get((pick % paths.len().max(1) as u64) as usize) else {
                    eprintln!("soak: no wrinkle file on disk to rewrite");
                    return;
                };
                // What another program would write: the file on disk with its first
                // fibre moved, or a line the parser refuses.
                let result = agesim_core::layers::wrinkles::wrinkle_file::load(path)
                    .or_else(|_| {
                        // The file is the broken one: mend it from the document.
                        let w = self
                            .wrinkles()
                            .iter()
                            .find(|w| w.path.as_ref() == Some(path));
                        w.map(|w| w.file.clone()).ok_or_else(|| {
                            agesim_core::Error::io(
                                path,
                                std::io::Error::other("not in the document"),
                            )
                        })
                    })
                    .map(|mut file| {
                        if let Some(g) = file.groups.first_mut()
                            && let Ok(f) = g.fibre.with_ends(
                                [g.fibre.ma()[0], (g.fibre.ma()[1] + 0.001).min(1.0)],
                                g.fibre.mb(),
                            )
                        {
                            g.fibre = f;
                        }
                        let mut text = agesim_core::layers::wrinkles::wrinkle_file::write(&file);
                        if broken {
                            text += "ma=not-a-number\n";
                        }
                        text
                    })
                    .and_then(|text| {
                        agesim_core::output::export::write_atomically(path, |w| {
                            std::io::Write::write_all(w, text.as_bytes())
                        })
                    });
                if let Err(e) = result {
                    eprintln!("soak: could not rewrite {}: {e}", path.display());
                }
                if broken && let Some(run) = &mut self.harness.soak {
                    run.broken = path.display().to_string();
                }
            }
            Action::TouchMask => {
                if let Some(mask) = self.doc.project.large.mask.clone()
                    && let Ok(bytes) = std::fs::read(&mask)
                {
                    let _ = agesim_core::output::export::write_atomically(&mask, |w| {
                        std::io::Write::write_all(w, &bytes)
                    });
                }
            }
            Action::Quit => {
                let _ = std::fs::remove_dir_all(&run.dir);
                ctx.send_viewport_cmd(egui::ViewportCommand::Close);
            }
        }
        let (latest, reported) = (self.session.worker.latest, self.session.reported);
        if let Some(run) = &mut self.harness.soak {
            run.soak.observe(latest, reported);
        }
    }
}

/// Whether a field the soak drags (a number or a switch) sets how much the editor holds:
/// the hair's and the spots' densities. Memory may grow with them without a leak, so the
/// soak measures growth from after their last change.
fn sizes_the_caches(path: &str) -> bool {
    matches!(path, "hair.density_per_cm2" | "skin.spots_per_cm2")
}
