//! The central panel: the view's toolbar (layout, map kind, overlays, compare, landmarks),
//! the 3D head and the UV map side by side, and the markers that tie them (a click on the
//! head marks its UV on the map; the pointer over the map marks the surface point).

use super::command::Command;
use super::{EditorApp, Layout, Persisted};
use crate::editor::map_view::{self, FibreEdit, MapKind};

impl EditorApp {
    /// Draws the central panel in `central_frame`; returns the fibre edit made on the map
    /// and the wrinkle files it edits.
    pub(super) fn central_ui(
        &mut self,
        ui: &mut egui::Ui,
        frame: &mut eframe::Frame,
        central_frame: egui::Frame,
    ) -> (Option<FibreEdit>, Vec<agesim_core::scene::WrinkleSource>) {
        let kind = self.persisted.map_view.kind;
        let fitted = self.session.snapshot.fitted;
        let wrinkles = self.wrinkles().to_vec();
        let render_state = frame
            .wgpu_render_state()
            .cloned()
            .or_else(|| self.render_state.clone());
        // While the age plays or the pointer drags, the governor sets the view's quality
        // from the measured frame interval (a lower resolution, upscaled, and less):
        // interaction stays fluid on a CPU adapter or a busy machine; everything returns
        // on the first still frame.
        let moving = self.persisted.playback.playing
            || ui.input(|i| i.pointer.any_down())
            || self.harness.dragging();
        let now = std::time::Instant::now();
        let interval_ms = self
            .last_frame_at
            .map_or(f64::NAN, |t| (now - t).as_secs_f64() * 1e3);
        self.last_frame_at = Some(now);
        let quality = self.governor.frame(moving, interval_ms);
        if let Some(v) = &mut self.viewport {
            v.quality = quality;
        }
        let mut compare_changed = false;
        self.landmark_view_sync();
        let fibre_edit = egui::CentralPanel::default()
            .frame(central_frame)
            .show(ui, |ui| {
                let toolbar = toolbar_ui(ui, &mut self.persisted, self.landmark_mode.is_some());
                compare_changed = toolbar.compare_changed;
                for command in toolbar.commands {
                    self.run(command, ui.ctx());
                }
                ui.label(
                    egui::RichText::new(
                        "head: drag orbit · right-drag pan · scroll zoom · Shift+drag light · double-click frame   map: drag a handle to move a fibre",
                    )
                    .weak()
                    .small(),
                );
                let layout = if self.viewport.is_none() { Layout::Map } else { self.persisted.layout };
                let avail = ui.available_rect_before_wrap();
                let (head_rect, map_rect) = match layout {
                    Layout::Both => {
                        let mid = avail.center().x;
                        (
                            Some(egui::Rect::from_min_max(avail.min, egui::pos2(mid - 2.0, avail.max.y))),
                            Some(egui::Rect::from_min_max(egui::pos2(mid + 2.0, avail.min.y), avail.max)),
                        )
                    }
                    Layout::Head => (Some(avail), None),
                    Layout::Map => (None, Some(avail)),
                };
                if let (Some(r), Some(viewport), Some(rs)) = (head_rect, &mut self.viewport, &render_state) {
                    let mut child = ui.new_child(egui::UiBuilder::new().max_rect(r));
                    let rect = viewport.ui(&mut child, rs, &self.session.snapshot, &mut self.doc.project);
                    if self.persisted.compare
                        && let Some(b) = self.session.snapshot.compare.as_deref()
                    {
                        super::compare::compare_ui(
                            &mut child,
                            rs,
                            rect,
                            viewport,
                            b,
                            &self.doc.project,
                            self.persisted.compare_years,
                            &mut self.persisted.divider,
                        );
                    }
                }
                let mut edit = None;
                if let Some(r) = map_rect {
                    let mut child = ui.new_child(egui::UiBuilder::new().max_rect(r));
                    let picture = self.map_image(kind).is_some();
                    edit = map_view::map_view_ui(&mut child, &mut self.persisted.map_view, picture, &wrinkles, fitted);
                    self.fill_map_picture(&child, kind, render_state.as_ref());
                }
                ui.allocate_rect(avail, egui::Sense::hover());
                edit
            })
            .inner;
        if compare_changed {
            self.submit(false, "compare");
        }
        // The normal-map pictures are baked only while one is shown.
        let wants_normals = self.persisted.map_view.kind.normal_picture();
        // So are the shape's pictures.
        let wants_shape = self.persisted.map_view.kind == MapKind::Shape;
        if wants_normals != self.baked_normal_picture || wants_shape != self.baked_shape_pictures {
            self.baked_normal_picture = wants_normals;
            self.baked_shape_pictures = wants_shape;
            self.submit(false, "map view");
        }
        // The shape's movement on the head while the map view shows it.
        if let Some(v) = &mut self.viewport {
            v.show_shape = self.persisted.map_view.kind == MapKind::Shape;
        }
        // Head ↔ map: a click on the head marks its UV on the map; the pointer over the
        // map marks the surface point on the head.
        // A fitted head's fibres are on the template's chart: its UVs go through the
        // correspondence both ways (the head's own maps are in its own UVs).
        let snapshot = &self.session.snapshot;
        let through = snapshot
            .correspondence
            .as_ref()
            .filter(|_| self.persisted.map_view.kind.on_fibre_chart(snapshot.fitted));
        if let Some(v) = &mut self.viewport {
            if let Some(p) = v.picked.take() {
                let uv = match through {
                    Some(c) => c.template_uv_at(p.uv),
                    None => Some(p.uv),
                };
                self.persisted.map_view.marker_uv = uv.map(|uv| [uv.x, uv.y]);
            }
            let hover = self.persisted.map_view.hover_uv;
            if hover != self.last_hover_uv {
                self.last_hover_uv = hover;
                let head_uv = hover.map(glam::Vec2::from).and_then(|uv| match through {
                    // Every other texel of the map, within 2 % of the chart.
                    Some(c) => c.head_uv_of(uv, 2, 0.02),
                    None => Some(uv),
                });
                v.marker = match (head_uv, &snapshot.mesh) {
                    (Some(uv), Some(mesh)) => {
                        crate::editor::pick::uv_to_surface(mesh, uv).map(|p| p.position)
                    }
                    _ => None,
                };
            }
        }
        (fibre_edit, wrinkles)
    }

    /// Fills the map view's picture place of this frame: on the GPU adapter, when the
    /// square lies whole in the view, the map and its layout in one paint callback
    /// (`editor::map_gpu`: on a CPU rasteriser egui's two blended images cost about 10 ms
    /// a frame); else as egui images (zoomed past the view, or no adapter).
    fn fill_map_picture(
        &mut self,
        ui: &egui::Ui,
        kind: MapKind,
        render_state: Option<&eframe::egui_wgpu::RenderState>,
    ) {
        let Some(place) = map_view::PicturePlace::of(&self.persisted.map_view) else {
            return;
        };
        let layout_shown = map_view::shows_layout(&self.persisted.map_view);
        if let (Some(rs), true, Some(map)) = (render_state, place.fits(), self.map_image(kind)) {
            let layout = layout_shown.then(|| self.layout_image(kind)).flatten();
            let gpu = self
                .map_gpu
                .get_or_insert_with(|| crate::editor::map_gpu::MapGpu::new(rs));
            let callback = gpu.callback(rs, &map, layout.as_ref(), place.square);
            place.fill(ui, egui::Shape::Callback(callback));
            return;
        }
        let ctx = ui.ctx().clone();
        let mut textures: Vec<egui::TextureId> = self
            .texture(&ctx, kind)
            .map(|t| t.id())
            .into_iter()
            .collect();
        if layout_shown {
            textures.extend(self.layout_texture(&ctx, kind).map(|t| t.id()));
        }
        place.fill(ui, place.images(&textures));
    }
}

/// What the toolbar asked for beyond the view settings it edits.
struct Toolbar {
    /// The compare view was switched or its age changed (a bake is needed).
    compare_changed: bool,
    /// Landmarks toggled, the head framed.
    commands: Vec<Command>,
}

/// The view's toolbar over `persisted` (layout, map kind, overlays, compare); the
/// landmarks toggle shows `landmarks_on`.
fn toolbar_ui(ui: &mut egui::Ui, persisted: &mut Persisted, landmarks_on: bool) -> Toolbar {
    let mut out = Toolbar {
        compare_changed: false,
        commands: Vec::new(),
    };
    ui.horizontal_wrapped(|ui| {
        for (layout, name) in [
            (Layout::Both, "head | map"),
            (Layout::Head, "head"),
            (Layout::Map, "map"),
        ] {
            ui.selectable_value(&mut persisted.layout, layout, name);
        }
        ui.separator();
        let kind = persisted.map_view.kind;
        egui::ComboBox::new("map kind", "map")
            .selected_text(kind.name())
            .show_ui(ui, |ui| {
                for k in MapKind::ALL {
                    ui.selectable_value(&mut persisted.map_view.kind, k, k.name());
                }
            });
        ui.checkbox(&mut persisted.map_view.show_fibres, "fibres");
        ui.checkbox(&mut persisted.map_view.show_layout, "UV layout");
        let was = (persisted.compare, persisted.compare_years);
        ui.checkbox(&mut persisted.compare, "compare with");
        ui.add_enabled(
            persisted.compare,
            egui::DragValue::new(&mut persisted.compare_years)
                .range(0.0..=150.0)
                .suffix(" years"),
        );
        out.compare_changed = was != (persisted.compare, persisted.compare_years);
        let mut on = landmarks_on;
        if ui
            .toggle_value(&mut on, "landmarks")
            .on_hover_text("show the head's landmarks: drag to correct, click to place, Fit")
            .clicked()
        {
            out.commands.push(Command::ToggleLandmarks);
        }
        if ui.button("frame head").clicked() {
            out.commands.push(Command::FrameHead);
        }
    });
    out
}
