//! Scripted runs: the UI benchmark (`--bench-ui`) and the screenshot (`--screenshot`).

use super::{EditorApp, Layout};

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
        let Some(bench) = &mut self.bench else {
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
            self.session.reported,
            self.session.worker.latest,
            hairs,
            years,
        ) {
            crate::editor::bench_ui::Action::None => {}
            crate::editor::bench_ui::Action::BigBake => {
                self.submit_sized((4096, 4096), "4096² bake")
            }
            crate::editor::bench_ui::Action::SetAge(t) => self.set_age(t, true),
            crate::editor::bench_ui::Action::Play => self.persisted.playback.playing = true,
            crate::editor::bench_ui::Action::PlayHeadOnly => {
                self.persisted.layout = Layout::Head;
                self.persisted.playback.playing = true;
            }
            crate::editor::bench_ui::Action::Stop => self.persisted.playback.playing = false,
            crate::editor::bench_ui::Action::Quit => {
                ctx.send_viewport_cmd(egui::ViewportCommand::Close)
            }
        }
    }

    pub(super) fn maybe_screenshot(&mut self, ctx: &egui::Context) {
        let Some(path) = self.options.screenshot.clone() else {
            return;
        };
        if self.session.snapshot.large.is_some() && self.idle() {
            self.frames_with_maps += 1;
        }
        ctx.request_repaint();
        if self.frames_with_maps >= self.options.frames.max(1) && !self.screenshot_requested {
            self.screenshot_requested = true;
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
