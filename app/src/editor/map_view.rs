//! The 2D map view: a baked map over the head's UV square, every muscle fibre drawn as an
//! arrow from mA to mB with its influence area outlined; drag an end (circle) or the
//! whole fibre (square), select it for the inspector. Scroll to zoom, drag with the right
//! or middle button to pan; double-click the background to reset the view.

use agesim_core::layers::wrinkles::muscle::Fibre;
use agesim_core::scene::WrinkleSource;
use egui::{Color32, Pos2, Rect, Sense, Stroke, Vec2, pos2, vec2};

/// Which map the view shows.
#[derive(Clone, Copy, Debug, PartialEq, Eq, serde::Serialize, serde::Deserialize)]
pub enum MapKind {
    LargeHeight,
    LargeNormal,
    MicroHeight,
    MicroNormal,
    Transition,
    Fine,
    Mask,
    /// The large-wrinkle heights in the head's own UV layout (what the 3D view and the
    /// exports use): for checking an imported head's output.
    LargeHead,
    /// How far the shape moves the head at full age (docs/models.md §13), in its own UVs;
    /// the 3D view shows it on the head while this is shown.
    Shape,
}

impl MapKind {
    /// Which normal-map picture this kind shows, (large, micro): the worker bakes them
    /// only while shown.
    pub fn normal_picture(self) -> (bool, bool) {
        (self == Self::LargeNormal, self == Self::MicroNormal)
    }

    pub const ALL: [MapKind; 9] = [
        MapKind::LargeHeight,
        MapKind::LargeNormal,
        MapKind::LargeHead,
        MapKind::MicroHeight,
        MapKind::MicroNormal,
        MapKind::Transition,
        MapKind::Fine,
        MapKind::Mask,
        MapKind::Shape,
    ];

    pub fn name(self) -> &'static str {
        match self {
            MapKind::LargeHeight => "large wrinkles: height",
            MapKind::LargeNormal => "large wrinkles: normal",
            MapKind::MicroHeight => "micro-relief tile: height",
            MapKind::MicroNormal => "micro-relief tile: normal",
            MapKind::Transition => "hair transition",
            MapKind::Fine => "fine-wrinkle tile",
            MapKind::Mask => "large-wrinkle mask",
            MapKind::LargeHead => "large wrinkles: the head's own UVs",
            MapKind::Shape => "shape: movement at full age",
        }
    }

    /// Whether the map covers a head's UV square (not a repeated tile).
    pub fn is_uv_map(self) -> bool {
        !matches!(
            self,
            MapKind::MicroHeight | MapKind::MicroNormal | MapKind::Fine
        )
    }

    /// Whether the map is on the chart the fibres are authored on (the template's; for a
    /// head read at its own UVs every UV map is): fibres are drawn and edited over it.
    /// A `fitted` head's own layout (its large map read through the fit, its hair
    /// transition) is not.
    pub fn on_fibre_chart(self, fitted: bool) -> bool {
        match self {
            MapKind::LargeHeight | MapKind::LargeNormal | MapKind::Mask => true,
            MapKind::Transition | MapKind::LargeHead | MapKind::Shape => !fitted,
            MapKind::MicroHeight | MapKind::MicroNormal | MapKind::Fine => false,
        }
    }
}

/// Pan/zoom and selection of the map view (persisted).
#[derive(Clone, Debug, serde::Serialize, serde::Deserialize)]
#[serde(default)]
pub struct MapViewState {
    pub kind: MapKind,
    pub zoom: f32,
    pub offset: [f32; 2],
    pub show_fibres: bool,
    /// Draw the mesh's UV layout over the map.
    pub show_layout: bool,
    /// (file index, group index) of the selected fibre.
    #[serde(skip)]
    pub selected: Option<(usize, usize)>,
    /// Where the UV square was drawn last frame (for tests and picking).
    #[serde(skip)]
    pub last_square: Option<egui::Rect>,
    /// The place kept for the map's picture last frame, and the view's rectangle (the
    /// app fills it: [`picture_shapes`]).
    #[serde(skip)]
    pub picture_slot: Option<(egui::layers::ShapeIdx, Rect)>,
    /// A UV to mark (the point clicked on the head).
    #[serde(skip)]
    pub marker_uv: Option<[f32; 2]>,
    /// The UV under the pointer, when it is over the UV square.
    #[serde(skip)]
    pub hover_uv: Option<[f32; 2]>,
}

impl Default for MapViewState {
    fn default() -> Self {
        Self {
            kind: MapKind::LargeHeight,
            zoom: 1.0,
            offset: [0.0, 0.0],
            show_fibres: true,
            show_layout: true,
            selected: None,
            last_square: None,
            picture_slot: None,
            marker_uv: None,
            hover_uv: None,
        }
    }
}

/// A fibre changed by a drag in the view.
pub struct FibreEdit {
    pub file: usize,
    pub group: usize,
    pub fibre: Fibre,
    pub dragging: bool,
}

/// UV ↔ screen mapping of the shown square.
#[derive(Clone, Copy)]
pub struct UvRect(pub Rect);

impl UvRect {
    pub fn to_screen(self, uv: [f32; 2]) -> Pos2 {
        pos2(
            self.0.left() + uv[0] * self.0.width(),
            self.0.top() + (1.0 - uv[1]) * self.0.height(),
        )
    }

    pub fn to_uv(self, p: Pos2) -> [f32; 2] {
        [
            (p.x - self.0.left()) / self.0.width(),
            1.0 - (p.y - self.0.top()) / self.0.height(),
        ]
    }

    fn uv_per_px(self) -> Vec2 {
        vec2(1.0 / self.0.width(), -1.0 / self.0.height())
    }
}

/// Draws the view and returns the fibre edit of this frame, if any. `picture`: whether
/// there is a map to show; its place under the fibres is kept in
/// [`MapViewState::picture_slot`] for the app to fill ([`picture_shapes`]).
pub fn map_view_ui(
    ui: &mut egui::Ui,
    state: &mut MapViewState,
    picture: bool,
    wrinkles: &[WrinkleSource],
    fitted: bool,
) -> Option<FibreEdit> {
    let (rect, background) = ui.allocate_exact_size(ui.available_size(), Sense::click_and_drag());
    let painter = ui.painter_at(rect);
    // No background fill: the panel's colour shows through (on a CPU rasteriser every
    // filled pixel costs, ≈ 1–2 fps of scrubbing with the map view beside the head).
    // Zoom about the pointer, pan with the secondary/middle button.
    if let Some(hover) = background.hover_pos() {
        let scroll = ui.input(|i| i.smooth_scroll_delta.y + i.zoom_delta().ln() * 200.0);
        if scroll != 0.0 {
            let old = state.zoom;
            state.zoom = (state.zoom * (scroll * 0.003).exp()).clamp(0.25, 40.0);
            let k = state.zoom / old;
            let c = rect.center() + Vec2::from(state.offset);
            let new_c = hover + (c - hover) * k;
            state.offset = (new_c - rect.center()).into();
        }
    }
    if background.dragged_by(egui::PointerButton::Secondary)
        || background.dragged_by(egui::PointerButton::Middle)
    {
        let d = background.drag_delta();
        state.offset = [state.offset[0] + d.x, state.offset[1] + d.y];
    }
    if background.double_clicked() {
        state.zoom = 1.0;
        state.offset = [0.0, 0.0];
    }
    let side = rect.width().min(rect.height()) * 0.95 * state.zoom;
    let square =
        Rect::from_center_size(rect.center() + Vec2::from(state.offset), Vec2::splat(side));
    let uv = UvRect(square);
    state.last_square = Some(square);
    state.hover_uv = background
        .hover_pos()
        .filter(|p| square.contains(*p))
        .map(|p| uv.to_uv(p));
    state.picture_slot = None;
    if picture {
        state.picture_slot = Some((painter.add(egui::Shape::Noop), rect));
    } else {
        painter.text(
            rect.center(),
            egui::Align2::CENTER_CENTER,
            "baking…",
            egui::FontId::proportional(16.0),
            Color32::GRAY,
        );
    }
    painter.rect_stroke(
        square,
        0.0,
        Stroke::new(1.0, Color32::from_gray(90)),
        egui::StrokeKind::Outside,
    );
    if let Some(m) = state.marker_uv {
        let at = uv.to_screen(m);
        let colour = Color32::from_rgb(255, 200, 60);
        painter.line_segment(
            [at - vec2(9.0, 0.0), at + vec2(9.0, 0.0)],
            Stroke::new(2.0, colour),
        );
        painter.line_segment(
            [at - vec2(0.0, 9.0), at + vec2(0.0, 9.0)],
            Stroke::new(2.0, colour),
        );
        painter.text(
            at + vec2(10.0, -10.0),
            egui::Align2::LEFT_BOTTOM,
            format!("{:.3}; {:.3}", m[0], m[1]),
            egui::FontId::monospace(11.0),
            colour,
        );
    }
    if !(state.show_fibres && state.kind.on_fibre_chart(fitted)) {
        return None;
    }
    let mut edit = None;
    for (fi, file) in wrinkles.iter().enumerate() {
        for (gi, group) in file.file.groups.iter().enumerate() {
            let f = &group.fibre;
            let selected = state.selected == Some((fi, gi));
            let colour = if selected {
                Color32::from_rgb(255, 200, 60)
            } else {
                Color32::from_rgb(90, 200, 255)
            };
            let (a, b) = (uv.to_screen(f.ma()), uv.to_screen(f.mb()));
            draw_influence(&painter, uv, f, colour.gamma_multiply(0.5));
            painter.arrow(
                a,
                b - a,
                Stroke::new(if selected { 2.5 } else { 1.5 }, colour),
            );
            let id = ui.scope_id().with(("fibre", fi, gi));
            for (handle, pos, shape_square) in
                [(0, a, false), (1, b, false), (2, a + (b - a) * 0.5, true)]
            {
                let hit = Rect::from_center_size(pos, Vec2::splat(14.0));
                let r = ui.interact(hit, id.with(handle), Sense::click_and_drag());
                let hot = r.hovered() || r.dragged();
                let fill = if hot { Color32::WHITE } else { colour };
                if shape_square {
                    painter.rect_filled(Rect::from_center_size(pos, Vec2::splat(7.0)), 1.0, fill);
                } else {
                    painter.circle_filled(pos, 4.5, fill);
                }
                if r.clicked() || r.drag_started() {
                    state.selected = Some((fi, gi));
                }
                if r.dragged() || r.drag_stopped() {
                    let d = r.drag_delta() * uv.uv_per_px();
                    let (mut ma, mut mb) = (f.ma(), f.mb());
                    if handle != 1 {
                        ma = [ma[0] + d.x, ma[1] + d.y];
                    }
                    if handle != 0 {
                        mb = [mb[0] + d.x, mb[1] + d.y];
                    }
                    if let Ok(fibre) = f.with_ends(ma, mb) {
                        edit = Some(FibreEdit {
                            file: fi,
                            group: gi,
                            fibre,
                            dragging: !r.drag_stopped(),
                        });
                    }
                }
            }
        }
    }
    edit
}

/// Whether the UV layout is drawn over the map this frame.
pub fn shows_layout(state: &MapViewState) -> bool {
    state.show_layout && state.kind.is_uv_map()
}

/// The place kept for the map's picture this frame ([`MapViewState::picture_slot`]).
#[derive(Clone, Copy, Debug)]
pub struct PicturePlace {
    slot: egui::layers::ShapeIdx,
    /// The view's rectangle (the picture is clipped to it).
    pub view: Rect,
    /// Where the UV square lies.
    pub square: Rect,
}

impl PicturePlace {
    /// `state`'s place, when a picture is to be shown.
    pub fn of(state: &MapViewState) -> Option<Self> {
        let ((slot, view), square) = (state.picture_slot?, state.last_square?);
        Some(Self { slot, view, square })
    }

    /// Whether the whole square lies in the view: a paint callback (which fills its own
    /// rectangle) can draw it.
    pub fn fits(&self) -> bool {
        self.view.contains_rect(self.square)
    }

    /// Puts `shape` in the place.
    pub fn fill(&self, ui: &egui::Ui, shape: egui::Shape) {
        ui.painter_at(self.view).set(self.slot, shape);
    }

    /// The egui images of the map and of the layout over it, on the square.
    pub fn images(&self, textures: &[egui::TextureId]) -> egui::Shape {
        let whole = Rect::from_min_max(pos2(0.0, 0.0), pos2(1.0, 1.0));
        egui::Shape::Vec(
            textures
                .iter()
                .map(|&t| egui::Shape::image(t, self.square, whole, Color32::WHITE))
                .collect(),
        )
    }
}

/// The outline of a fibre's influence area: points within W·L of the segment (docs/models.md §2's
/// At(d) > 0), a capsule around mA–mB.
fn draw_influence(painter: &egui::Painter, uv: UvRect, f: &Fibre, colour: Color32) {
    let (a, b) = (f.ma(), f.mb());
    let (dx, dy) = (b[0] - a[0], b[1] - a[1]);
    let len = (dx * dx + dy * dy).sqrt();
    if len <= 0.0 {
        return;
    }
    let r = f.rel_width() * len;
    let (nx, ny) = (-dy / len * r, dx / len * r);
    let angle0 = ny.atan2(nx);
    let mut pts = Vec::new();
    // Half circle around mB from +n to −n, then around mA from −n back to +n.
    for (centre, start) in [(b, angle0), (a, angle0 + std::f32::consts::PI)] {
        for i in 0..=16 {
            let t = start - std::f32::consts::PI * i as f32 / 16.0;
            pts.push(uv.to_screen([centre[0] + r * t.cos(), centre[1] + r * t.sin()]));
        }
    }
    pts.push(pts[0]);
    painter.add(egui::Shape::line(pts, Stroke::new(1.0, colour)));
}
