//! The age timeline along the bottom: the layers' age curves with draggable onset / full
//! handles, a years ruler, the scrubbable playhead (a slider in years), play / pause /
//! loop and speed.

use agesim_core::age::AgeCurve;
use agesim_core::project::{Project, fields};
use egui::{Color32, Pos2, Rect, Sense, Stroke, pos2, vec2};

/// Playback state (persisted: speed and loop).
#[derive(Clone, Debug, serde::Serialize, serde::Deserialize)]
#[serde(default)]
pub struct Playback {
    #[serde(skip)]
    pub playing: bool,
    pub looping: bool,
    /// Years per second.
    pub speed: f32,
}

impl Default for Playback {
    fn default() -> Self {
        Self {
            playing: false,
            looping: true,
            speed: 10.0,
        }
    }
}

/// What the timeline asks for this frame.
#[derive(Default)]
pub struct TimelineEdit {
    /// A new age t (scrub or playback), and whether it is still moving.
    pub t: Option<(f32, bool)>,
    /// A curve handle moved: (field path, years, still dragging).
    pub curve: Option<(&'static str, f32, bool)>,
}

/// The colour of each age curve, in the order of the project's table
/// (`agesim_core::project::fields::age_curves`); a curve past the list takes gray.
const CURVE_COLOURS: [Color32; 9] = [
    Color32::from_rgb(90, 200, 255),
    Color32::from_rgb(160, 230, 120),
    Color32::from_rgb(240, 170, 90),
    Color32::from_rgb(230, 110, 140),
    Color32::from_rgb(220, 220, 220),
    Color32::from_rgb(190, 130, 80),
    Color32::from_rgb(200, 170, 120),
    Color32::from_rgb(240, 90, 90),
    Color32::from_rgb(170, 140, 230),
];

/// The project's age curves shown: (what, field path, curve, colour).
fn curves(p: &Project) -> Vec<(&'static str, &'static str, AgeCurve, Color32)> {
    agesim_core::project::fields::age_curves(p)
        .into_iter()
        .enumerate()
        .map(|(i, r)| {
            let colour = CURVE_COLOURS.get(i).copied().unwrap_or(Color32::GRAY);
            (r.what, r.path, r.curve, colour)
        })
        .collect()
}

pub fn timeline_ui(ui: &mut egui::Ui, project: &Project, playback: &mut Playback) -> TimelineEdit {
    let mut edit = TimelineEdit::default();
    let mapping = project.age.mapping();
    let (young, old) = (mapping.young_years, mapping.old_years);
    let mut years = mapping.years(project.age.t);

    // Playback advances the age by wall-clock time.
    if playback.playing {
        // Wall-clock time since the last frame, so playback runs in real time however
        // fast frames come.
        let dt = ui.input(|i| i.unstable_dt).min(0.25);
        years += dt * playback.speed;
        if years > old {
            if playback.looping {
                years = young;
            } else {
                years = old;
                playback.playing = false;
            }
        }
        edit.t = Some((mapping.t(years), playback.playing));
        ui.ctx().request_repaint();
    }

    ui.horizontal(|ui| {
        let label = if playback.playing { "Pause" } else { "Play" };
        if ui.button(label).clicked() {
            playback.playing = !playback.playing;
            if !playback.playing {
                edit.t = Some((mapping.t(years), false));
            }
        }
        ui.checkbox(&mut playback.looping, "loop");
        egui::ComboBox::new("speed", "speed")
            .selected_text(format!("{} years/s", playback.speed))
            .show_ui(ui, |ui| {
                for s in [2.0, 5.0, 10.0, 20.0] {
                    ui.selectable_value(&mut playback.speed, s, format!("{s} years/s"));
                }
            });
        ui.separator();
        ui.spacing_mut().slider_width = (ui.available_width() - 190.0).max(100.0);
        let shown = years;
        let r = ui.add(
            egui::Slider::new(&mut years, young..=old)
                .text("age (years)")
                .fixed_decimals(1),
        );
        // The slider rounds what it shows to 0.1 year; only a larger change is the user's.
        if r.changed() && (years - shown).abs() > 0.051 {
            playback.playing = false;
            edit.t = Some((mapping.t(years), r.dragged()));
        } else {
            years = shown;
        }
        if r.drag_stopped() {
            edit.t = Some((mapping.t(years), false));
        }
    });

    // Curves over the same years axis, with a ruler.
    let (rect, _) = ui.allocate_exact_size(vec2(ui.available_width(), 92.0), Sense::hover());
    let painter = ui.painter_at(rect);
    // An outline, not a fill: on a CPU rasteriser every filled pixel of every frame costs
    // (this strip is ≈ 120k pixels, ≈ 4 ms a frame on llvmpipe).
    painter.rect_stroke(
        rect,
        2.0,
        Stroke::new(1.0, Color32::from_gray(45)),
        egui::StrokeKind::Inside,
    );
    let plot = Rect::from_min_max(rect.min + vec2(8.0, 6.0), rect.max - vec2(8.0, 18.0));
    let x_of = |y: f32| plot.left() + (y - young) / (old - young) * plot.width();
    let y_of = |f: f32| plot.bottom() - f * plot.height();
    let mut decade = (young / 10.0).ceil() * 10.0;
    while decade <= old {
        let x = x_of(decade);
        painter.line_segment(
            [pos2(x, plot.top()), pos2(x, plot.bottom() + 4.0)],
            Stroke::new(1.0, Color32::from_gray(50)),
        );
        painter.text(
            pos2(x, rect.bottom() - 2.0),
            egui::Align2::CENTER_BOTTOM,
            format!("{decade:.0}"),
            egui::FontId::proportional(11.0),
            Color32::GRAY,
        );
        decade += 10.0;
    }
    for (i, (name, path, curve, colour)) in curves(project).into_iter().enumerate() {
        let pts: Vec<Pos2> = (0..=120)
            .map(|k| {
                let y = young + (old - young) * k as f32 / 120.0;
                pos2(x_of(y), y_of(curve.factor(y)))
            })
            .collect();
        painter.add(egui::Shape::line(pts, Stroke::new(1.5, colour)));
        painter.text(
            // Two columns of five names: the strip is five lines tall.
            pos2(
                plot.left() + 4.0 + 130.0 * (i / 5) as f32,
                plot.top() + 12.0 * (i % 5) as f32,
            ),
            egui::Align2::LEFT_TOP,
            name,
            egui::FontId::proportional(10.0),
            colour,
        );
        for (which, y, f) in [
            ("onset_years", curve.onset_years, 0.0),
            ("full_years", curve.full_years, 1.0),
        ] {
            if !(young..=old).contains(&y) {
                continue;
            }
            let p = pos2(x_of(y), y_of(f));
            let id = ui.scope_id().with((path, which));
            let r = ui.interact(
                Rect::from_center_size(p, vec2(12.0, 12.0)),
                id,
                Sense::drag(),
            );
            painter.circle_filled(
                p,
                if r.hovered() || r.dragged() { 5.5 } else { 3.5 },
                colour,
            );
            if (r.dragged() || r.drag_stopped())
                && let Some(pointer) = r.interact_pointer_pos()
            {
                let years = young + (pointer.x - plot.left()) / plot.width() * (old - young);
                // The field's own &'static path, from the engine's table.
                if let Ok(field) = fields::find(&format!("{path}.{which}")) {
                    edit.curve = Some((
                        field.path,
                        years.round().clamp(0.0, 150.0),
                        !r.drag_stopped(),
                    ));
                }
            }
        }
    }
    // The playhead.
    let x = x_of(years);
    painter.line_segment(
        [pos2(x, rect.top()), pos2(x, rect.bottom())],
        Stroke::new(2.0, Color32::from_rgb(255, 200, 60)),
    );
    edit
}
