//! The 3D view: the renderer (`agesim-render`) draws the head into its own colour and
//! depth targets on eframe's wgpu device; an egui paint callback blits the colour target
//! into egui's pass (`agesim_render::Blit`). Drag to orbit, right-drag to pan, scroll to
//! zoom, Shift+drag to move the light, double-click to frame the head.
//!
//! A frame is encoded and submitted only when something it shows changed (the maps, the
//! project's view, age or shading, the size): on a CPU adapter an unchanged view costs
//! nothing. Uploads happen when the worker's snapshot brings a new map.

use std::sync::Arc;

use agesim_core::project::Project;
use agesim_render::{FrameParams, Renderer, ViewId};
use eframe::egui_wgpu;
use egui::{Rect, Sense};
use glam::Vec3;

use super::worker::Snapshot;
use crate::view::{self, Uploaded};

/// The 3D view's colour target: 8-bit with the sRGB encoding done by the skin and hair
/// shaders, copied as it is into egui's (non-sRGB) frame. An sRGB format would make the
/// CPU rasteriser decode four texels per shown pixel: drawing the view's image cost
/// ≈ 29 ms of every frame on llvmpipe at 1280×800.
const VIEW_FORMAT: eframe::wgpu::TextureFormat = eframe::wgpu::TextureFormat::Rgba8Unorm;

/// Which age a frame shows: the document's, or the compare view's.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Shown {
    Document = 0,
    Compare = 1,
}

/// The panes of [`Viewport::panes`].
const MAIN: usize = Shown::Document as usize;
const COMPARE: usize = Shown::Compare as usize;

/// One of the renderer's views as shown: what it was given, the key of its last frame
/// and the blit's bind group for its current colour target.
struct Pane {
    view: ViewId,
    /// The compare pane tracks only its own layers (the large-wrinkle map, the
    /// micro-relief tile, the aged colour, the shape, the brows); the main pane also the
    /// shared mesh, fine tile and hair.
    uploaded: Uploaded,
    last: Option<(FrameParams, [u32; 2], Uploaded, Uploaded)>,
    shown: Option<(u64, eframe::wgpu::BindGroup)>,
}

impl Pane {
    fn new(view: ViewId) -> Self {
        Self {
            view,
            uploaded: Uploaded::default(),
            last: None,
            shown: None,
        }
    }
}

pub struct Viewport {
    /// Show the head's colour tinted by the shape's movement (the map view shows the
    /// shape: docs/models.md §13).
    pub show_shape: bool,
    /// The quality of the next frames: full when still; while the age plays or the view
    /// or a slider moves, what the frame-time governor chose (`governor`: a lower
    /// resolution, upscaled; sparse hair; fewer relief steps; no contact shadows).
    pub quality: super::governor::Quality,
    renderer: Renderer,
    /// Shows the colour target in egui's pass, with its bind group for the current
    /// target (remade when the renderer recreates its targets).
    blit: Arc<agesim_render::Blit>,
    /// The renderer's views as shown: [`MAIN`] the document's age, [`COMPARE`] (made
    /// on the first compare frame) the compare age, with its own targets and
    /// age-dependent layers on the same renderer.
    panes: Vec<Pane>,
    /// The head's centre, the orbit's target (mesh units).
    centre: Vec3,
    /// How long one unit of the shown mesh is, metres (the main view's snapshot's).
    metres_per_unit: f32,
    /// The view's last size, points (for framing).
    aspect: (f32, f32),
    /// A new mesh arrived: frame it on the next frame (a head of the artist's own).
    frame_pending: bool,
    /// The head's units changed by this factor since the last frame: the camera's
    /// distance in metres follows, so the view stays the same.
    rescale: f32,
    pan: Vec3,
    /// Time to encode and submit the last frame, ms.
    pub encode_ms: f64,
    /// The hairs of the last frame's age (count(t)).
    pub hairs_drawn: u32,
    /// The last frame drew one hair in this many (1: all of them).
    pub sparse_hair: u32,
    pub error: Option<String>,
    /// The surface point clicked last (taken by the app to show it on the map).
    pub picked: Option<super::pick::SurfacePoint>,
    /// A surface point to mark on the head (the point under the pointer on the map).
    pub marker: Option<Vec3>,
    /// The guided landmark mode's dots (set by the app each frame; `None`: mode off).
    pub landmarks: Option<LandmarkOverlay>,
    /// A landmark dragged or placed this frame: its name and new point (scene
    /// coordinates, on the surface).
    pub landmark_edit: Option<(&'static str, Vec3)>,
    /// The landmark whose dot the pointer is dragging.
    dragging_landmark: Option<&'static str>,
    /// Where each landmark's dot was drawn last frame.
    pub landmark_dots: Vec<(&'static str, egui::Pos2)>,
    mesh: Option<Arc<agesim_core::Mesh>>,
}

/// The landmarks drawn over the head in the guided landmark mode: labelled dots that can
/// be dragged over the surface; a click elsewhere places `selected`.
#[derive(Clone, Debug, Default)]
pub struct LandmarkOverlay {
    /// Placed points, scene coordinates.
    pub points: Vec<(&'static str, Vec3)>,
    /// The landmark a click on the head places (and whose dot is highlighted).
    pub selected: Option<&'static str>,
}

/// How near (points) the pointer must be to a dot to drag it.
const LANDMARK_GRAB_PT: f32 = 10.0;
/// How near (a fraction of the head's size) the surface seen at a dot must be to its
/// landmark for the dot to count as visible (grabbable).
const LANDMARK_SEEN_WITHIN: f32 = 0.03;

impl Viewport {
    pub fn new(rs: &egui_wgpu::RenderState) -> Result<Self, agesim_render::RenderError> {
        Ok(Self {
            show_shape: false,
            quality: super::governor::LEVELS[0],
            renderer: Renderer::new(&rs.device, &rs.queue, VIEW_FORMAT)?,
            blit: Arc::new(agesim_render::Blit::new(&rs.device, rs.target_format)),
            panes: vec![Pane::new(ViewId::MAIN)],
            centre: Vec3::ZERO,
            metres_per_unit: 1.0,
            aspect: (1.0, 1.0),
            frame_pending: false,
            rescale: 1.0,
            pan: Vec3::ZERO,
            encode_ms: 0.0,
            hairs_drawn: 0,
            sparse_hair: 1,
            error: None,
            picked: None,
            marker: None,
            landmarks: None,
            landmark_edit: None,
            dragging_landmark: None,
            landmark_dots: Vec::new(),
            mesh: None,
        })
    }

    /// Uploads what the snapshot brought that pane `i`'s view does not have yet (the
    /// head's colour tinted by the shape's movement while [`Self::show_shape`]).
    fn upload(&mut self, i: usize, snapshot: &Snapshot) {
        let tinted;
        let layers = match &snapshot.shape_overlay {
            Some(overlay) if self.show_shape => {
                tinted = crate::view::Layers {
                    aged: Some(overlay.clone()),
                    ..snapshot.layers.clone()
                };
                &tinted
            }
            _ => &snapshot.layers,
        };
        let pane = &mut self.panes[i];
        let result = if i == MAIN {
            if let Some(mesh) = &snapshot.layers.mesh
                && self.mesh.as_ref().is_none_or(|m| !Arc::ptr_eq(m, mesh))
            {
                self.centre = mesh.bounds().centre();
                self.mesh = Some(mesh.clone());
                self.frame_pending = true;
            }
            // The same head in other units (a dense head shown at the units its size
            // gives, then at its landmarks'): the camera stays where it is on the head.
            let units = snapshot.layers.metres_per_unit;
            if !self.frame_pending && units != self.metres_per_unit && units > 0.0 {
                self.rescale *= units / self.metres_per_unit.max(1e-12);
            }
            self.metres_per_unit = units;
            pane.uploaded.upload(&mut self.renderer, layers)
        } else {
            pane.uploaded
                .upload_age_layers(&mut self.renderer, pane.view, layers)
        };
        if let Err(e) = result {
            self.error = Some(e.to_string());
        }
    }

    /// Frames the head: the project's default view, no pan.
    pub fn reset(&mut self, project: &mut Project) {
        let d = agesim_core::project::ViewSection::default();
        project.view.camera_yaw_deg = d.camera_yaw_deg;
        project.view.camera_pitch_deg = d.camera_pitch_deg;
        project.view.camera_distance_m = d.camera_distance_m;
        self.pan = Vec3::ZERO;
        // The default distance is the built-in head's: a head of its own is framed at its
        // own size (in the view's last shape).
        if project.mesh.path.is_some()
            && let Some(mesh) = &self.mesh
        {
            let (w, h) = self.aspect;
            project.view.camera_distance_m = framing_distance(
                mesh.bounds().size().length() * 0.5,
                project.view.fov_deg,
                w / h,
            ) * self.metres_per_unit;
        }
    }

    /// Draws the view into the rest of `ui`; mouse input edits `project.view`.
    pub fn ui(
        &mut self,
        ui: &mut egui::Ui,
        rs: &egui_wgpu::RenderState,
        snapshot: &Snapshot,
        project: &mut Project,
    ) -> Rect {
        let (rect, response) = ui.allocate_exact_size(ui.available_size(), Sense::click_and_drag());
        self.aspect = (rect.width().max(1.0), rect.height().max(1.0));
        if std::mem::take(&mut self.frame_pending) && project.mesh.path.is_some() {
            // A head of the artist's own just arrived: framed, as "frame head" would.
            self.reset(project);
        }
        let rescale = std::mem::replace(&mut self.rescale, 1.0);
        if rescale != 1.0 && rescale.is_finite() && project.mesh.path.is_some() {
            project.view.camera_distance_m *= rescale;
        }
        // The guided landmark mode: a drag that starts on a dot moves it over the surface
        // (and does not orbit); a click places the selected landmark.
        self.landmark_edit = None;
        let clip = self.clip_from_world(project, rect);
        let pick_at = |viewport: &Self, pos: egui::Pos2| {
            let mesh = viewport.mesh.as_ref()?;
            let ndc = glam::Vec2::new(
                2.0 * (pos.x - rect.left()) / rect.width() - 1.0,
                1.0 - 2.0 * (pos.y - rect.top()) / rect.height(),
            );
            let (origin, dir) = super::pick::view_ray(clip, ndc);
            super::pick::ray_pick(mesh, origin, dir)
        };
        if let Some(overlay) = &self.landmarks {
            // The dot under the press, not under the pointer once the drag has begun.
            if response.drag_started_by(egui::PointerButton::Primary)
                && let Some(pos) = ui.input(|i| i.pointer.press_origin())
            {
                // A dot behind the head (the far ear seen from the front) is not grabbed
                // through the face: the surface seen at the dot must be the landmark's.
                let hidden_beyond = self.mesh.as_ref().map_or(f32::INFINITY, |m| {
                    LANDMARK_SEEN_WITHIN * m.bounds().size().length()
                });
                let near: Vec<(&'static str, f32)> = overlay
                    .points
                    .iter()
                    .filter_map(|(name, p)| Some((*name, *p, to_screen(clip, rect, *p)?)))
                    .filter(|(_, _, at)| at.distance(pos) <= LANDMARK_GRAB_PT)
                    .filter(|(_, p, at)| {
                        pick_at(self, *at)
                            .is_none_or(|hit| hit.position.distance(*p) <= hidden_beyond)
                    })
                    .map(|(name, _, at)| (name, at.distance(pos)))
                    .collect();
                // Dots can overlap (the nose tip over the base of the nose): the one
                // selected in the list wins, else the nearest.
                self.dragging_landmark = near
                    .iter()
                    .find(|(name, _)| overlay.selected == Some(*name))
                    .or_else(|| near.iter().min_by(|a, b| a.1.total_cmp(&b.1)))
                    .map(|(name, _)| *name);
            }
        } else {
            self.dragging_landmark = None;
        }
        if let Some(name) = self.dragging_landmark {
            if let Some(pos) = response.interact_pointer_pos()
                && let Some(hit) = pick_at(self, pos)
            {
                self.landmark_edit = Some((name, hit.position));
            }
            if !response.dragged() {
                self.dragging_landmark = None;
            }
        } else {
            self.interact(ui, &response, project);
        }
        if response.clicked()
            && let Some(pos) = response.interact_pointer_pos()
        {
            self.picked = pick_at(self, pos);
            if let (Some(overlay), Some(hit)) = (&self.landmarks, self.picked)
                && let Some(name) = overlay.selected
            {
                self.landmark_edit = Some((name, hit.position));
            }
        }
        if self.render(Shown::Document, ui.ctx(), rs, snapshot, project, rect) {
            self.show(Shown::Document, ui.painter(), rect);
        }
        // The camera as this frame drew it (the orbit above may have moved it).
        let clip = self.clip_from_world(project, rect);
        if let Some(at) = self.marker.and_then(|p| to_screen(clip, rect, p)) {
            let colour = egui::Color32::from_rgb(255, 200, 60);
            ui.painter()
                .circle_stroke(at, 7.0, egui::Stroke::new(2.0, colour));
            ui.painter().circle_filled(at, 2.0, colour);
        }
        self.landmark_dots.clear();
        if let Some(overlay) = &self.landmarks {
            let painter = ui.painter().with_clip_rect(rect);
            let font = egui::FontId::proportional(11.0);
            let mut dots = Vec::new();
            for (name, p) in &overlay.points {
                let Some(at) = to_screen(clip, rect, *p) else {
                    continue;
                };
                self.landmark_dots.push((name, at));
                let chosen =
                    overlay.selected == Some(*name) || self.dragging_landmark == Some(*name);
                let colour = if chosen {
                    egui::Color32::from_rgb(255, 200, 60)
                } else {
                    egui::Color32::from_rgb(90, 200, 255)
                };
                let galley = painter.layout_no_wrap((*name).to_owned(), font.clone(), colour);
                dots.push((at, chosen, colour, galley));
            }
            // Labels placed so none covers another or a dot (close landmarks: the mouth,
            // the nose), on the side of the face their dot is on.
            let spots: Vec<(egui::Pos2, egui::Vec2)> =
                dots.iter().map(|(at, _, _, g)| (*at, g.size())).collect();
            let labels = place_labels(&spots);
            for ((at, chosen, colour, galley), label) in dots.into_iter().zip(labels) {
                painter.circle_filled(at, if chosen { 5.0 } else { 4.0 }, colour);
                painter.circle_stroke(at, 6.0, egui::Stroke::new(1.0, egui::Color32::BLACK));
                if label.distance_to_pos(at) > 12.0 {
                    painter.line_segment(
                        [at, label.center()],
                        egui::Stroke::new(1.0, colour.gamma_multiply(0.6)),
                    );
                }
                painter.rect_filled(label.expand(1.0), 2.0, egui::Color32::from_black_alpha(150));
                painter.galley(label.min, galley, colour);
            }
        }
        if let Some(e) = &self.error {
            ui.painter().text(
                rect.left_top() + egui::vec2(8.0, 8.0),
                egui::Align2::LEFT_TOP,
                e,
                egui::FontId::proportional(13.0),
                egui::Color32::from_rgb(255, 110, 90),
            );
        }
        rect
    }

    /// Whether a landmark's dot is being dragged.
    pub fn dragging_landmark(&self) -> bool {
        self.dragging_landmark.is_some()
    }

    /// The view's clip-from-world matrix for `rect` (as the renderer uses it).
    fn clip_from_world(&self, project: &Project, rect: Rect) -> glam::Mat4 {
        let camera = view::camera(project, self.metres_per_unit, self.centre + self.pan);
        camera.clip_from_world(rect.width() / rect.height().max(1.0))
    }

    /// The numbers of the main view's last frame (for tests and diagnostics).
    pub fn last_frame(&self) -> Option<&FrameParams> {
        self.panes[MAIN].last.as_ref().map(|(params, ..)| params)
    }

    /// Shows `age`'s latest frame over `rect`, through `painter`'s clip rectangle (the
    /// compare age: the part right of the divider).
    pub fn show(&self, age: Shown, painter: &egui::Painter, rect: Rect) {
        if let Some((_, bind_group)) = self.panes.get(age as usize).and_then(|p| p.shown.as_ref()) {
            painter.add(egui_wgpu::Callback::new_paint_callback(
                rect,
                ShowFrame {
                    blit: self.blit.clone(),
                    bind_group: bind_group.clone(),
                },
            ));
        }
    }

    /// Uploads what changed and, when anything it shows changed, encodes a frame of
    /// `age` of `rect`'s size; returns whether there is a frame to show. `snapshot` and
    /// `project` are that age's: for [`Shown::Compare`] the compare scene's snapshot and
    /// the document at the compare age, drawn into a second view of the same renderer
    /// (the mesh, the hair and the fine tile are not uploaded twice).
    pub fn render(
        &mut self,
        age: Shown,
        ctx: &egui::Context,
        rs: &egui_wgpu::RenderState,
        snapshot: &Snapshot,
        project: &Project,
        rect: Rect,
    ) -> bool {
        if age == Shown::Compare && self.panes.len() <= COMPARE {
            let view = self.renderer.add_view();
            self.panes.push(Pane::new(view));
        }
        let i = age as usize;
        self.upload(i, snapshot);
        if snapshot.layers.mesh.is_none() {
            return self.panes[i].shown.is_some();
        }
        // The age shown is the document's (every age-dependent number follows it at
        // once); the maps are the last baked ones.
        // A head that just arrived is framed on the next frame (`ui` frames the project's
        // view); this frame draws it framed already, not at the last head's distance.
        let framed;
        let project = if i == MAIN && self.frame_pending && project.mesh.path.is_some() {
            let mut p = project.clone();
            self.reset(&mut p);
            framed = p;
            &framed
        } else {
            project
        };
        let mpu = snapshot.layers.metres_per_unit;
        // A change of units not yet applied to the project's distance (next frame) is
        // applied here, so no frame shows the head at the wrong distance.
        let camera = view::camera(project, mpu / self.rescale, self.centre + self.pan);
        let head = snapshot.layers.head();
        let mut params = view::frame_params(project, head, project.age.t, camera);
        // The governor's quality: the still frame that follows a move draws everything.
        let q = self.quality;
        params.hair.sparse = q.sparse_hair;
        if !q.shadows {
            params.light.shadow_reach = 0.0;
        }
        (params.skin.linear_steps, params.skin.binary_steps) = (
            params.skin.linear_steps.min(q.relief_steps.0),
            params.skin.binary_steps.min(q.relief_steps.1),
        );
        // The pixels egui's paint callback covers (its viewport rounds the rectangle's
        // edges to pixels): at full resolution one texel lands on one pixel.
        let ppp = ctx.pixels_per_point();
        let scale = q.scale.clamp(0.1, 1.0);
        let pixels =
            |a: f32, b: f32| (((b * ppp).round() - (a * ppp).round()) * scale).round() as u32;
        let size = [
            pixels(rect.left(), rect.right()).clamp(16, 4096),
            pixels(rect.top(), rect.bottom()).clamp(16, 4096),
        ];
        // The shared layers are the main pane's: a change there redraws both.
        let key = (
            params,
            size,
            self.panes[MAIN].uploaded.clone(),
            self.panes[i].uploaded.clone(),
        );
        if self.panes[i].last.as_ref() == Some(&key) {
            return self.panes[i].shown.is_some();
        }
        let start = std::time::Instant::now();
        let mut encoder =
            rs.device
                .create_command_encoder(&eframe::wgpu::CommandEncoderDescriptor {
                    label: Some("agesim editor 3D view"),
                });
        let view = self.panes[i].view;
        match self
            .renderer
            .encode_view(view, &mut encoder, &params, (size[0], size[1]))
        {
            Ok(()) => {
                rs.queue.submit([encoder.finish()]);
                let generation = self.renderer.target_generation_of(view);
                let pane = &mut self.panes[i];
                if pane.shown.as_ref().is_none_or(|(g, _)| *g != generation)
                    && let Some(colour) = self.renderer.colour_view_of(view)
                {
                    pane.shown = Some((generation, self.blit.bind(&rs.device, colour)));
                }
                if i == MAIN {
                    self.hairs_drawn = if params.hair.enabled {
                        self.renderer.hair_count(params.age)
                    } else {
                        0
                    };
                    self.sparse_hair = if params.hair.sparse {
                        self.renderer.sparse_hair_stride()
                    } else {
                        1
                    };
                    self.error = None;
                }
            }
            Err(e) => self.error = Some(e.to_string()),
        }
        if i == MAIN {
            self.encode_ms = start.elapsed().as_secs_f64() * 1e3;
        }
        self.panes[i].last = Some(key);
        self.panes[i].shown.is_some()
    }

    fn interact(&mut self, ui: &egui::Ui, response: &egui::Response, project: &mut Project) {
        let v = &mut project.view;
        let shift = ui.input(|i| i.modifiers.shift);
        if response.dragged_by(egui::PointerButton::Primary) {
            let d = response.drag_delta();
            if shift {
                v.light_yaw_deg = (v.light_yaw_deg - d.x * 0.5).rem_euclid(360.0);
                v.light_pitch_deg = (v.light_pitch_deg + d.y * 0.5).clamp(-89.0, 89.0);
            } else {
                v.camera_yaw_deg = (v.camera_yaw_deg - d.x * 0.4).rem_euclid(360.0);
                v.camera_pitch_deg = (v.camera_pitch_deg + d.y * 0.4).clamp(-85.0, 85.0);
            }
        }
        if response.dragged_by(egui::PointerButton::Secondary)
            || response.dragged_by(egui::PointerButton::Middle)
        {
            let d = response.drag_delta();
            let (yaw, pitch) = (
                v.camera_yaw_deg.to_radians(),
                v.camera_pitch_deg.to_radians(),
            );
            let right = Vec3::new(yaw.cos(), 0.0, -yaw.sin());
            let up = Vec3::new(
                -pitch.sin() * yaw.sin(),
                pitch.cos(),
                -pitch.sin() * yaw.cos(),
            );
            let scale = v.camera_distance_m / self.metres_per_unit.max(1e-9) * 0.0015;
            self.pan += (-right * d.x + up * d.y) * scale;
        }
        if response.hovered() {
            let scroll = ui.input(|i| i.smooth_scroll_delta.y + i.zoom_delta().ln() * 200.0);
            if scroll != 0.0 {
                v.camera_distance_m =
                    (v.camera_distance_m * (-scroll * 0.002).exp()).clamp(0.02, 20.0);
            }
        }
        if response.double_clicked() {
            self.reset(project);
        }
    }
}

/// The camera distance (mesh units) at which a sphere of `radius` around the orbit's
/// target fills a view of vertical field of view `fov_deg` and `aspect` (width / height),
/// with a margin: the smaller of the two half-angles decides.
fn framing_distance(radius: f32, fov_deg: f32, aspect: f32) -> f32 {
    let half_v = (fov_deg.to_radians() * 0.5).clamp(0.01, 1.5);
    let half_h = (half_v.tan() * aspect).atan();
    1.1 * radius / half_v.min(half_h).sin().max(1e-3)
}

/// The paint callback that blits the view's frame into egui's render pass.
struct ShowFrame {
    blit: Arc<agesim_render::Blit>,
    bind_group: eframe::wgpu::BindGroup,
}

impl egui_wgpu::CallbackTrait for ShowFrame {
    fn paint(
        &self,
        _info: egui::PaintCallbackInfo,
        render_pass: &mut eframe::wgpu::RenderPass<'static>,
        _resources: &egui_wgpu::CallbackResources,
    ) {
        self.blit.draw(render_pass, &self.bind_group);
    }
}

/// Where `p` (scene coordinates) shows in `rect`, `None` behind the camera.
fn to_screen(clip: glam::Mat4, rect: Rect, p: Vec3) -> Option<egui::Pos2> {
    let c = clip * p.extend(1.0);
    (c.w > 0.0).then(|| {
        egui::pos2(
            rect.left() + (c.x / c.w + 1.0) * 0.5 * rect.width(),
            rect.top() + (1.0 - c.y / c.w) * 0.5 * rect.height(),
        )
    })
}

/// Where each landmark's label goes: for each dot (its screen point and its label's
/// size) a rectangle that overlaps no label placed before it and no dot, trying spots
/// around the dot from the nearest out, on the side of the face the dot is on (right of
/// the dots' mean x: to the right). A label with no free spot nearby takes the first one.
pub fn place_labels(dots: &[(egui::Pos2, egui::Vec2)]) -> Vec<egui::Rect> {
    use egui::{Rect, pos2, vec2};
    let mean_x = dots.iter().map(|(p, _)| p.x).sum::<f32>() / dots.len().max(1) as f32;
    let dot_box = |p: egui::Pos2| Rect::from_center_size(p, vec2(12.0, 12.0));
    let mut placed: Vec<Rect> = Vec::new();
    for &(at, size) in dots {
        let right = at.x >= mean_x;
        let candidates = (0..6).flat_map(|ring| {
            let d = 7.0 + 12.0 * ring as f32;
            let dys = [-d - size.y, d, -size.y * 0.5, -d - size.y * 2.0];
            dys.into_iter().flat_map(move |dy| {
                let out = if right { d } else { -d - size.x };
                let inward = if right { -d - size.x } else { d };
                [out, inward].map(|dx| Rect::from_min_size(pos2(at.x + dx, at.y + dy), size))
            })
        });
        let free = |r: &Rect| {
            !placed.iter().any(|p| p.intersects(*r))
                && !dots.iter().any(|(p, _)| dot_box(*p).intersects(*r))
        };
        let mut first = None;
        let mut chosen = None;
        for r in candidates {
            first.get_or_insert(r);
            if free(&r) {
                chosen = Some(r);
                break;
            }
        }
        let r = chosen.or(first).unwrap_or(Rect::from_min_size(at, size));
        placed.push(r);
    }
    placed
}

#[cfg(test)]
mod label_tests {
    use super::*;

    #[test]
    fn close_landmarks_get_labels_that_do_not_overlap() {
        // The mouth and nose of a small head on screen: six dots within 20 px.
        let size = egui::vec2(60.0, 12.0);
        let dots: Vec<(egui::Pos2, egui::Vec2)> = [
            (300.0, 300.0),
            (310.0, 304.0),
            (320.0, 300.0),
            (305.0, 315.0),
            (315.0, 315.0),
            (310.0, 290.0),
        ]
        .iter()
        .map(|&(x, y)| (egui::pos2(x, y), size))
        .collect();
        let labels = place_labels(&dots);
        for (i, a) in labels.iter().enumerate() {
            for b in &labels[i + 1..] {
                assert!(!a.intersects(*b), "{a:?} overlaps {b:?}");
            }
            for (p, _) in &dots {
                assert!(!a.contains(*p), "{a:?} covers the dot {p:?}");
            }
        }
        // The subject's left (screen right) labels go right.
        assert!(labels[2].min.x >= 320.0, "{:?}", labels[2]);
    }
}
