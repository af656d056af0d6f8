//! The compare view: a second age right of a draggable divider, in the same camera.

use agesim_core::project::Project;

use crate::editor::viewport::{Shown, Viewport};
use crate::editor::worker::Snapshot;

/// The compare view over the state it shows: the right part of `rect` (from `divider`
/// on, a share of the width, which the divider's drag edits) shows `project` at
/// `compare_years` from `snapshot_b`, in the same camera, drawn by the 3D view's renderer
/// `v` into a second set of targets.
#[allow(clippy::too_many_arguments)]
pub(super) fn compare_ui(
    ui: &mut egui::Ui,
    rs: &eframe::egui_wgpu::RenderState,
    rect: egui::Rect,
    v: &mut Viewport,
    snapshot_b: &Snapshot,
    project: &Project,
    compare_years: f32,
    divider: &mut f32,
) {
    let mut project_b = project.clone();
    project_b.age.t = project_b.age.mapping().t(compare_years);
    let x = rect.left() + rect.width() * *divider;
    if v.render(Shown::Compare, ui.ctx(), rs, snapshot_b, &project_b, rect) {
        let right = egui::Rect::from_min_max(egui::pos2(x, rect.top()), rect.max);
        v.show(Shown::Compare, &ui.painter().with_clip_rect(right), rect);
    }
    let handle = egui::Rect::from_center_size(
        egui::pos2(x, rect.center().y),
        egui::vec2(14.0, rect.height()),
    );
    let r = ui.interact(
        handle,
        ui.scope_id().with("compare divider"),
        egui::Sense::drag(),
    );
    if r.dragged() {
        *divider = ((x + r.drag_delta().x - rect.left()) / rect.width()).clamp(0.02, 0.98);
    }
    let colour = egui::Color32::from_rgb(255, 200, 60);
    ui.painter().line_segment(
        [egui::pos2(x, rect.top()), egui::pos2(x, rect.bottom())],
        egui::Stroke::new(if r.hovered() || r.dragged() { 3.0 } else { 2.0 }, colour),
    );
    let years_a = project.age.mapping().years(project.age.t);
    for (pos, align, text) in [
        (
            rect.left_bottom() + egui::vec2(10.0, -10.0),
            egui::Align2::LEFT_BOTTOM,
            format!("{years_a:.0} years"),
        ),
        (
            rect.right_bottom() + egui::vec2(-10.0, -10.0),
            egui::Align2::RIGHT_BOTTOM,
            format!("{compare_years:.0} years"),
        ),
    ] {
        ui.painter()
            .text(pos, align, text, egui::FontId::proportional(18.0), colour);
    }
}
